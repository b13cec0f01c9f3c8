# strip.awk - replace the solution regions of the given lecture steps by stubs.
#
# A solution region in the source reads
#       /* STEP(latlong): direction -> (u, v): theta = acos z, phi = atan2(y, x) (slide 12) */
#       /* STUB: uv->u = 0; uv->v = 0; return -1; */
#       ... the solution ...
#       /* END STEP(latlong) */
# With `steps` (space separated) naming latlong, the region becomes
#       /* TODO(latlong): direction -> (u, v): theta = acos z, phi = atan2(y, x) (slide 12) */
#       uv->u = 0; uv->v = 0; return -1;
# Regions of other steps keep their solution (the marker lines stay as comments).
# Every marker is checked, for every step (stripped or not): a STEP line must be followed by its
# STUB line, regions do not nest, and each END STEP closes the open region of the same name.  A
# malformed marker is an error (exit 2): a starter must never ship a solution by mistake.
# usage: awk -v steps="latlong cdf" -f strip.awk FILE
function fail(msg) { print "strip.awk: " FILENAME ":" NR ": " msg > "/dev/stderr"; failed = 1; exit 2 }
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
        line = $0
        if ((getline stub) <= 0 || !match(stub, /\/\* STUB: .* \*\//)) {
            NR--; fail("STEP(" name ") without a STUB line after it")
        }
        code = substr(stub, RSTART + 9, RLENGTH - 12)
        if (name in want) {
            indent = $0; sub(/[^ \t].*$/, "", indent)
            sub(/\/\* STEP\(/, "/* TODO(", line)
            print line
            print indent code
            skipping = 1
        } else {
            print line
            print stub
        }
        next
    }
    print
}
END { if (!failed && open != "") { print "strip.awk: " FILENAME ": STEP(" open ") never ends" > "/dev/stderr"; exit 2 } }
