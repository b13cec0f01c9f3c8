# probe.awk - the complete solution with a probe at the start of every solution region, for
# tests/starter/check: which test runs which step's code.  After a region's STUB comment (the
# markers as strip.awk reads them) it inserts one line,
#       { extern void starter_probe(const char *); static int seen_;
#         if (!seen_) { seen_ = 1; starter_probe("NAME"); } }   (on one line)
# where starter_probe (tests/starter/probe.c, added to the probed tree only) records NAME for
# the running test.  A region whose STEP comment starts in column 0 (at file scope, where no
# statement can go) gets no probe: its name goes to the file `unprobed` names, and the check
# runs every test in that step's starter.  Markers are assumed well formed (strip.awk checks).
# usage: awk -v unprobed=FILE -f probe.awk FILE.c
function comment_end(   l) { # print up to the line that closes the comment begun on this one
    print
    if (index($0, "*/")) return
    while ((getline l) > 0) { print l; if (index(l, "*/")) return }
}
{
    if (match($0, /\/\* STEP\([a-z0-9-]+\): /)) {
        name = substr($0, RSTART + 8, RLENGTH - 11)
        indent = $0; sub(/[^ \t].*$/, "", indent)
        comment_end()
        if ((getline) <= 0) exit
        comment_end() # the STUB comment
        if (indent == "") print name >> unprobed
        else print indent "{ extern void starter_probe(const char *); static int seen_; " \
            "if (!seen_) { seen_ = 1; starter_probe(\"" name "\"); } }"
        next
    }
    print
}
