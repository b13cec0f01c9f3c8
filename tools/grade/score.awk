# tools/grade/score.awk: one submission's points (tools/grade/run; docs/grading.md, "Points").
#   awk -v build=VERDICT -f tools/grade/score.awk POINTS tests/steps TESTS SCENES
# POINTS is tools/grade/points.txt; TESTS has a line "TEST VERDICT" for each test program run
# (ok, failed, timeout, ...); SCENES a line "NAME VERDICT" for each scene (pass, fail, ...).
# Prints one line per graded step and scene, in the points file's order, tab-separated:
#     step|scene  NAME  SCORE  MAX  passed|failed  VISIBILITY  WHY
# A step's tests can fail for another step's mistake (golden renders every step), so a failed test
# is charged to the step that explains it.  A graded step fails when
#   1. a test that no other graded step lists fails (its own test), or
#   2. every test it lists (but its + tests, which its stub passes) fails, or
#   3. a failed test that no step failed by 1 or 2 lists is charged to the steps that list it with
#      the largest share of their tests failing (the likeliest cause), repeated until every failed
#      test is charged.
# Every other step earns its points; its WHY names its failed tests and the failed step that
# explains each.  A scene earns its points when compare --test passes.  When the tree did not
# build (build != ok), nothing earns points.
BEGIN { FS = "[ \t]+" }
FILENAME == ARGV[1] && /^(step|scene)[ \t]/ {
    if ($1 == "step") { name = $2; pts = $3; vis = $4 }
    else { name = $3; sub(/.*\//, "", name); sub(/\.test$/, "", name); pts = $4; vis = $5 }
    if (pts !~ /^[0-9]+(\.[0-9]+)?$/) {
        bad = FILENAME ":" FNR ": points must be a number"
        exit 2
    }
    if (vis == "") vis = "visible"
    if (vis !~ /^(visible|hidden|after_due_date|after_published)$/) {
        bad = FILENAME ":" FNR ": visibility must be visible, hidden, after_due_date or" \
            " after_published"
        exit 2
    }
    order[++n] = $1 SUBSEP name; kind[n] = $1; nm[n] = name; max[n] = pts; visib[n] = vis
    if ($1 == "step" && pts > 0) { graded[name] = 1; where[name] = FILENAME ":" FNR }
    next
}
FILENAME == ARGV[2] && /^[a-z]/ {
    s = $1; sub(":", "", s)
    for (i = 2; i <= NF; i++) {
        t = $i; plus = sub(/^\+/, "", t)
        ntests[s]++; test[s, ntests[s]] = t; isplus[s, t] = plus
        if (!(t in listers)) alltests[++nall] = t
        listers[t] = listers[t] " " s
    }
    next
}
FILENAME == ARGV[3] { verdict[$1] = $2; next }
FILENAME == ARGV[4] { scene[$1] = $2; next }
function failing(t) { return (t in verdict) && verdict[t] != "ok" }
function graded_listers(t,    a, k, i, out) {
    k = split(listers[t], a, " "); out = ""
    for (i = 1; i <= k; i++) if (a[i] in graded) out = out " " a[i]
    return substr(out, 2)
}
function commas(x) { gsub(/ /, ", ", x); return x }
function share(s,    i, f) {
    f = 0
    for (i = 1; i <= ntests[s]; i++) f += failing(test[s, i])
    return f / ntests[s]
}
END {
    if (bad != "") { print "envtex: " bad > "/dev/stderr"; exit 2 }
    for (s in graded) if (!(s in ntests)) {
        print "envtex: " where[s] ": no step " s " in tests/steps" > "/dev/stderr"; exit 2
    }
    # 1 and 2
    for (j = 1; j <= n; j++) {
        s = nm[j]
        if (kind[j] != "step" || !(s in graded)) continue
        own = ""; all = 1; some = 0
        for (i = 1; i <= ntests[s]; i++) {
            t = test[s, i]
            if (failing(t) && graded_listers(t) == s) own = own ", " t
            if (!isplus[s, t]) { some = 1; if (!failing(t)) all = 0 }
        }
        if (own != "") why[s] = "a test of this step alone failed: " substr(own, 3)
        else if (some && all) why[s] = "every test of this step failed"
        if (s in why) failed[s] = 1
    }
    # 3: the failed tests no failed step lists, charged to their likeliest cause
    do {
        changed = 0
        for (m = 1; m <= nall; m++) {
            t = alltests[m]
            if (!failing(t)) continue
            k = split(graded_listers(t), a, " ")
            explained = 0; best = -1
            for (i = 1; i <= k; i++) {
                if (a[i] in failed) explained = 1
                if (share(a[i]) > best) best = share(a[i])
            }
            if (explained || k == 0) continue
            for (i = 1; i <= k; i++) if (share(a[i]) == best) {
                failed[a[i]] = 1; changed = 1
                why[a[i]] = sprintf("%s failed, and no other failed step explains it: of the" \
                    " steps it tests (%s), this one has the largest share of its tests failing" \
                    " (%d%%)", t, commas(graded_listers(t)), int(best * 100 + 0.5))
            }
        }
    } while (changed)
    for (j = 1; j <= n; j++) {
        s = nm[j]
        if (kind[j] == "scene") {
            v = (s in scene) ? scene[s] : "-"
            ok = build == "ok" && v == "pass"
            w = ok ? "its render passes compare --test against the reference" : \
                build != "ok" ? "not rendered: the tree did not build" : \
                v == "-" ? "not rendered" : \
                "its render: " v " (compare --test against the reference)"
        } else if (!(s in graded)) {
            continue
        } else if (build != "ok") {
            ok = 0; w = "not tested: the tree did not build"
        } else {
            ok = !(s in failed)
            if (!ok) w = why[s]
            else {
                w = ""
                for (i = 1; i <= ntests[s]; i++) {
                    t = test[s, i]
                    if (!failing(t)) continue
                    k = split(graded_listers(t), a, " "); by = ""
                    for (x = 1; x <= k; x++) if (a[x] in failed) by = by ", " a[x]
                    w = w "; " t " failed, explained by " substr(by, 3)
                }
                w = w == "" ? "all " ntests[s] " of its tests pass" : \
                    "its own tests pass" w
            }
        }
        printf "%s\t%s\t%s\t%s\t%s\t%s\t%s\n", kind[j], s, ok ? max[j] : 0, max[j], \
            ok ? "passed" : "failed", visib[j], w
    }
}
