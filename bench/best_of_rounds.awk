# Merges one harness's "key value" outputs of several rounds (the files, first round
# first) into one, in the first file's order: a time (key ending in _s) the least of the
# rounds, a rate (key holding "mrays") the most, memory (key holding "bytes") the least
# (Embree's varies by a tenth of a byte per triangle with its threads' allocations), any
# other value the first round's. Such a value (a count, a name) should be the same every
# round; one that is not is reported on stderr, and the exit status is 1.
FNR == 1 { round++ }
round == 1 { order[++n] = $1; value[$1] = $2; next }
!($1 in value) { printf "best_of_rounds: %s: key %s is not in the first round\n", FILENAME, $1 > "/dev/stderr"; bad = 1; next }
$1 ~ /_s$|bytes/ { if ($2 + 0 < value[$1] + 0) value[$1] = $2; next }
$1 ~ /mrays/ { if ($2 + 0 > value[$1] + 0) value[$1] = $2; next }
$2 != value[$1] {
    printf "best_of_rounds: %s: %s is %s, %s in the first round\n", FILENAME, $1, $2, value[$1] > "/dev/stderr"
    bad = 1
}
END {
    for (i = 1; i <= n; i++) print order[i], value[order[i]]
    exit bad
}
