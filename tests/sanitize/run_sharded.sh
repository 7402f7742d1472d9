#!/bin/sh
# Runs a GoogleTest binary as N shards in parallel (GTEST_TOTAL_SHARDS / GTEST_SHARD_INDEX), each shard's output in
# its own log, and fails if any shard fails (its log is then printed). Usage: run_sharded.sh N BINARY [gtest args]
set -u
n=$1; shift
bin=$1; shift
dir=$(mktemp -d)
pids=""
i=0
while [ "$i" -lt "$n" ]; do
    GTEST_TOTAL_SHARDS=$n GTEST_SHARD_INDEX=$i "$bin" "$@" > "$dir/shard$i.log" 2>&1 &
    pids="$pids $!"
    i=$((i + 1))
done
status=0
i=0
for pid in $pids; do
    if wait "$pid"; then
        tail -n 3 "$dir/shard$i.log"
    else
        echo "shard $i of $n failed:"; cat "$dir/shard$i.log"; status=1
    fi
    i=$((i + 1))
done
rm -rf "$dir"
exit $status
