# Turns bench/run.sh's rows (metric, unit, rtk double, rtk fixed, Embree; tab-separated,
# empty = not measured) into the printed table, the position against issue 22's goals,
# and the CSV and JSON files. Variables: header, fixed, csv, json, skipped, load.
BEGIN { FS = "\t"; sub(/; $/, "", skipped) }

function isnum(s) { return s ~ /^-?[0-9]+(\.[0-9]+)?$/ }
function ratio(a, b) { return isnum(a) && isnum(b) && b + 0 != 0 ? sprintf("%.2f", a / b) : "" }
# What a goal is judged on: the quotient itself, not the printed ratio (a string rounded
# to 0.01, which awk would compare as a string: "1.00" <= 1 is false).
function quot(a, b) { return isnum(a) && isnum(b) && b + 0 != 0 ? a / b : 0 }
function show(s) { return s == "" ? "-" : s }
function jstr(s) { gsub(/\\/, "\\\\", s); gsub(/"/, "\\\"", s); return "\"" s "\"" }
function jval(s) { return s == "" ? "null" : isnum(s) ? s + 0 : jstr(s) }

{
    n++
    metric[n] = $1; unit[n] = $2; d[n] = $3; f[n] = $4; e[n] = $5
    counted = unit[n] == "count" || unit[n] == "%"
    de[n] = counted ? "" : ratio(d[n], e[n])
    fe[n] = counted ? "" : ratio(f[n], e[n])
    fd[n] = counted ? "" : ratio(f[n], d[n])
    at[$1] = n
    if ($1 ~ /^render / && $2 == "s" && isnum($3) && isnum($4)) { logsum += log($3 / $4); renders++ }
}

# cpu: the same ratio from CPU time (1-thread targets), shown beside the wall-time one.
function target(text, value, met, cpu) {
    tn++
    ttext[tn] = text; tvalue[tn] = value; tcpu[tn] = cpu
    tmet[tn] = value == "" ? "unknown" : met ? "met" : "not met"
}

END {
    printf "%s\n", header
    if (load != "") printf "load average: %s\n", load
    fmt = "%-58s %-8s %11s %11s %11s %8s %8s %8s\n"
    printf "\n" fmt, "metric", "unit", "rtk double", "rtk fixed", "Embree", "dbl/Emb", "fix/Emb", "fix/dbl"
    fixed_note = fixed == 1 ? "-" : "not built"
    for (i = 1; i <= n; i++)
        printf fmt, metric[i], unit[i], show(d[i]), f[i] == "" ? fixed_note : f[i], show(e[i]), show(de[i]),
               show(fe[i]), show(fd[i])
    if (skipped != "") printf "not rendered: %s\n", skipped
    printf "ratios divide the values as shown: for times (s) lower is better, for Mrays/s higher.\n"
    printf "shadow rays are any-hit queries with t_max = light distance (rt_scene_any, rtcOccluded1).\n"
    printf "packets: the camera rays of 4 x 2 pixels, the shadow rays of their hits; rtk's stream queries\n"
    printf "(rt_scene_nearest_stream, rt_scene_any_stream) and Embree's rtcIntersect8, rtcOccluded8 (coherent flag).\n"

    # Issue 22's goals, for rtk double unless said otherwise.
    p = at["primary rays, 1 thread"]
    pc = at["primary rays, 1 thread, CPU time"]
    target("primary rays 1 thread, rtk/Embree >= 1", de[p], quot(d[p], e[p]) >= 1, de[pc])
    for (k = 1; k <= n; k++) {
        if (metric[k] ~ /^primary rays, [0-9]+ threads$/) pa = k
        else if (metric[k] ~ /^shadow rays, [0-9]+ threads$/) sa = k
        else if (metric[k] ~ /^primary packets, [0-9]+ threads$/) ppa = k
        else if (metric[k] ~ /^shadow packets, [0-9]+ threads$/) spa = k
        else if (metric[k] ~ /^primary packets \(/) pp = k
        else if (metric[k] ~ /^shadow packets \(/) sp = k
    }
    target("primary rays all threads, rtk/Embree >= 1", de[pa], quot(d[pa], e[pa]) >= 1)
    s1 = at["shadow rays, 1 thread"]
    sc = at["shadow rays, 1 thread, CPU time"]
    target("shadow rays 1 thread, rtk/Embree >= 1", de[s1], quot(d[s1], e[s1]) >= 1, de[sc])
    target("shadow rays all threads, rtk/Embree >= 1", de[sa], quot(d[sa], e[sa]) >= 1)
    target("primary packets 1 thread, rtk/Embree >= 1", de[pp], quot(d[pp], e[pp]) >= 1)
    target("primary packets all threads, rtk/Embree >= 1", de[ppa], quot(d[ppa], e[ppa]) >= 1)
    target("shadow packets 1 thread, rtk/Embree >= 1", de[sp], quot(d[sp], e[sp]) >= 1)
    target("shadow packets all threads, rtk/Embree >= 1", de[spa], quot(d[spa], e[spa]) >= 1)
    b = at["BVH build vs Embree 1 thread"]
    bc = at["BVH build vs Embree 1 thread, CPU time"]
    target("BVH build time, rtk/Embree (1 thread) <= 1", de[b], quot(d[b], e[b]) <= 1, de[bc])
    b2 = at["BVH build vs Embree all threads"]
    target("BVH build time, rtk/Embree (all threads) <= 1", de[b2], quot(d[b2], e[b2]) <= 1)
    m = at["BVH + mesh memory"]
    target("BVH + mesh memory, rtk/Embree <= 1", de[m], quot(d[m], e[m]) <= 1)
    target("fixed/double primary rays 1 thread >= 0.5", fd[p], quot(f[p], d[p]) >= 0.5, fd[pc])
    target("fixed/double shadow rays 1 thread >= 0.5", fd[s1], quot(f[s1], d[s1]) >= 0.5, fd[sc])
    mean = renders ? exp(logsum / renders) : 0
    speed = renders ? sprintf("%.2f", mean) : ""
    target("fixed/double render speed (geometric mean) >= 0.5", speed, mean >= 0.5)
    ag = at["primary rays agreeing with Embree ray by ray"]
    target("camera rays agreeing with Embree (%) >= 99.99", d[ag], d[ag] >= 99.99)
    ag = at["shadow rays agreeing with Embree ray by ray"]
    target("shadow rays agreeing with Embree (%) >= 99.99", d[ag], d[ag] >= 99.99)
    printf "\ngoals (issue 22), rtk double unless stated; \"cpu\" = the same ratio by CPU time:\n"
    for (i = 1; i <= tn; i++) {
        line = sprintf("  %-52s %8s  %-8s  %s", ttext[i], show(tvalue[i]), tmet[i], tcpu[i] == "" ? "" : "(cpu " tcpu[i] ")")
        sub(/ +$/, "", line)
        print line
    }

    print "section,metric,unit,rtk_double,rtk_fixed,embree,double_over_embree,fixed_over_embree,fixed_over_double" >csv
    for (i = 1; i <= n; i++)
        printf "%s,\"%s\",%s,%s,%s,%s,%s,%s,%s\n", metric[i] ~ /^render / ? "render" : "kernel", metric[i], unit[i],
               d[i], f[i], e[i], de[i], fe[i], fd[i] >csv

    printf "{\n  \"header\": %s,\n  \"load_average\": %s,\n  \"not_rendered\": %s,\n  \"rows\": [\n", jstr(header),
           jval(load), jstr(skipped) >json
    for (i = 1; i <= n; i++)
        printf "    {\"metric\": %s, \"unit\": %s, \"rtk_double\": %s, \"rtk_fixed\": %s, \"embree\": %s, " \
               "\"double_over_embree\": %s, \"fixed_over_embree\": %s, \"fixed_over_double\": %s}%s\n",
               jstr(metric[i]), jstr(unit[i]), jval(d[i]), jval(f[i]), jval(e[i]), jval(de[i]), jval(fe[i]),
               jval(fd[i]), i < n ? "," : "" >json
    printf "  ],\n  \"targets\": [\n" >json
    for (i = 1; i <= tn; i++)
        printf "    {\"target\": %s, \"value\": %s, \"value_by_cpu_time\": %s, \"status\": %s}%s\n",
               jstr(ttext[i]), jval(tvalue[i]), jval(tcpu[i]), jstr(tmet[i]), i < tn ? "," : "" >json
    printf "  ]\n}\n" >json
}
