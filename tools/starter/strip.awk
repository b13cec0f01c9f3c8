# strip.awk - replace the solution regions of the given lecture steps by stubs.
#
# A solution region in the source reads
#       /* STEP(latlong): direction -> (u, v): theta = acos z, phi = atan2(y, x)
#        * (slide 9 (Environment Map Representations)) */
#       /* STUB: uv->u = 0; uv->v = 0;
#        * return -1; */
#       ... the solution ...
#       /* END STEP(latlong) */
# The STEP comment and the STUB comment may each span lines (continuation lines start with
# " * ").  With `steps` (space separated) naming latlong, the region becomes
#       /* TODO(latlong): direction -> (u, v): theta = acos z, phi = atan2(y, x)
#        * (slide 9 (Environment Map Representations)) */
#       uv->u = 0; uv->v = 0;
#       return -1;
# Regions of other steps keep their solution (the marker lines stay as comments).
# Every marker is checked, for every step (stripped or not): a STEP comment must be followed by
# its STUB comment, regions do not nest, and each END STEP closes the open region of the same
# name.  A malformed marker is an error (exit 2): a starter must never ship a solution by mistake.
# usage: awk -v steps="latlong cdf" -f strip.awk FILE
function fail(msg) { print "strip.awk: " FILENAME ":" NR ": " msg > "/dev/stderr"; failed = 1; exit 2 }
# the rest of a comment that began on an earlier line: its lines until the one holding "*/"
function rest_of_comment(first,   text, l) {
    text = first
    while ((getline l) > 0) {
        text = text "\n" l
        if (index(l, "*/")) return text
    }
    fail("a comment that never ends")
}
BEGIN { n = split(steps, s, " "); for (i = 1; i <= n; i++) want[s[i]] = 1; open = ""; skipping = 0 }
{
    if (match($0, /\/\* END STEP\([a-z0-9-]+\) \*\//)) {
        name = substr($0, RSTART + 12, RLENGTH - 16)
        if (open == "") fail("END STEP(" name ") without a STEP(" name ") before it")
        if (name != open) fail("END STEP(" name ") inside STEP(" open ")")
        open = ""
        if (skipping) { skipping = 0; next }
        print
        next
    }
    if (skipping) next
    if (match($0, /\/\* STEP\([a-z0-9-]+\): /)) {
        name = substr($0, RSTART + 8, RLENGTH - 11)
        if (open != "") fail("STEP(" name ") inside STEP(" open ")")
        open = name
        step = index($0, "*/") ? $0 : rest_of_comment($0)
        if ((getline first) <= 0 || !match(first, /^[ \t]*\/\* STUB: /))
            fail("STEP(" name ") without a STUB comment after it")
        stub = index(first, "*/") ? first : rest_of_comment(first)
        if (name in want) {
            indent = $0; sub(/[^ \t].*$/, "", indent)
            sub(/\/\* STEP\(/, "/* TODO(", step)
            print step
            # the stub's code: its text without the comment's marks, a line per line
            k = split(stub, lines, "\n")
            for (j = 1; j <= k; j++) {
                code = lines[j]
                if (j == 1) sub(/^[ \t]*\/\* STUB: /, "", code)
                else sub(/^[ \t]*\* ?/, "", code)
                if (j == k) sub(/ ?\*\/[ \t]*$/, "", code)
                if (code != "") print indent code
            }
            skipping = 1
        } else {
            print step
            print stub
        }
        next
    }
    print
}
END { if (!failed && open != "") { print "strip.awk: " FILENAME ": STEP(" open ") never ends" > "/dev/stderr"; exit 2 } }
