#!/usr/bin/env bash
# A process limit on memory (ulimit -v, as a batch system sets one) that the body does
# not fit: refused before the body is built, with one `bapd: error:` line naming the
# limit and the fixes, a non-zero exit, no std::bad_alloc backtrace; a body that fits
# runs under the same limit.
#   memory_limit.sh RANKS
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
ranks="$1"
((ranks == 1)) && export OMPI_MCA_odls_base_sigkill_timeout=0 # (bad_input.sh explains)
work="faults_memory_limit_np$ranks"
rm -rf "$work" && mkdir -p "$work" || exit 1
plate=(-options_file_yaml "$BAPD_SOURCE_DIR/examples/plate_hole.yaml" -end_time 0.0005 -progress_interval 1000000)
# 1.26 million points (2.4 GB) under a 1 GB address space.
(ulimit -v 1000000 && bounded "$work/big.log" "$ranks" "${plate[@]}" -body_dx 0.0001 -output_dir "$work/big"; exit $STATUS)
STATUS=$?
log="$work/big.log"
stopped_cleanly "material points need about" "process limit" "ulimit -v" "-body_dx"
grep -q -e "bad_alloc" -e "terminate called" "$log" && fail "std::bad_alloc reached the user"
ok "a body over the process's memory limit refused before it is built, $ranks rank(s)"
(ulimit -v 1000000 && bounded "$work/small.log" "$ranks" "${plate[@]}" -body_dx 0.004 -output_dir "$work/small"; exit $STATUS)
STATUS=$?
log="$work/small.log"
((STATUS == 0)) || fail "a small body did not run under the same limit"
ok "a small body runs under it"
