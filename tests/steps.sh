# tests/steps.sh - the one reader of tests/steps (sourced by tests/run, tests/starter/check,
# tools/starter/make-starter and tests/docs/run-tests).  A line of tests/steps reads
#     step: test test +test ...
# where a test marked +name runs the step's code but passes with its stub.  Each function reads
# tests/steps of the working folder and prints one word per line.

# every step, in file order
steps_names() { awk '/^[a-z]/ { sub(":", "", $1); print $1 }' tests/steps; }

# the tests of step $1 as listed, + marks kept
steps_tests() { awk -v s="$1:" '$1 == s { for (i = 2; i <= NF; i++) print $i }' tests/steps; }

# the steps that list test $1 without a + (they need it to pass)
steps_needing() { awk -v t="$1" '/^[a-z]/ { for (i = 2; i <= NF; i++) if ($i == t) { sub(":", "", $1); print $1; next } }' tests/steps; }
