# strip.awk - replace the solution regions of the given lecture steps by stubs.
#
# A solution region in the source reads
#       /* STEP(latlong): direction -> (u, v): theta = acos z, phi = atan2(y, x) (slide 12) */
#       /* STUB: (void)d; (void)uv; return -1; */
#       ... the solution ...
#       /* END STEP(latlong) */
# With `steps` (space separated) naming latlong, the region becomes
#       /* TODO(latlong): direction -> (u, v): theta = acos z, phi = atan2(y, x) (slide 12) */
#       (void)d; (void)uv; return -1;
# Regions of other steps keep their solution (the marker lines stay as comments).
# usage: awk -v steps="latlong cdf" -f strip.awk FILE
BEGIN { n = split(steps, s, " "); for (i = 1; i <= n; i++) want[s[i]] = 1; skipping = "" }
{
    if (skipping != "") {
        if ($0 ~ "/\\* END STEP\\(" skipping "\\) \\*/") skipping = ""
        next
    }
    if (match($0, /\/\* STEP\([a-z0-9-]+\): /)) {
        name = substr($0, RSTART + 8, RLENGTH - 11)
        if (name in want) {
            indent = $0; sub(/[^ \t].*$/, "", indent)
            line = $0; sub(/\/\* STEP\(/, "/* TODO(", line)
            print line
            if ((getline stub) > 0 && match(stub, /\/\* STUB: .* \*\//)) {
                code = substr(stub, RSTART + 9, RLENGTH - 12)
                print indent code
            } else {
                print "strip.awk: " FILENAME ":" NR ": STEP(" name ") without a STUB line" > "/dev/stderr"
                exit 2
            }
            skipping = name
            next
        }
    }
    print
}
END { if (skipping != "") { print "strip.awk: " FILENAME ": STEP(" skipping ") never ends" > "/dev/stderr"; exit 2 } }
