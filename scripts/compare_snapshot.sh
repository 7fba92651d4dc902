#!/usr/bin/env bash
# Compares two snapshots of scripts/behaviour_snapshot.sh. HDF5 files: every dataset and
# attribute within 1e-12 relative (h5diff -p, from Debian's hdf5-tools), except the creation
# time. Text and JSON: identical, except the diagnosis' timing fields (wall and thread seconds).
# Prints one line per difference; exit 1 if any.
set -uo pipefail
old=$1
new=$2
status=0
for f in "$old"/*; do
  name=$(basename "$f")
  g="$new/$name"
  if [ ! -e "$g" ]; then echo "missing: $name"; status=1; continue; fi
  case "$name" in
    *.h5)
      if ! h5diff -p 1e-12 --exclude-attribute / "$f" "$g" > /tmp/h5diff.$$ 2>&1; then
        echo "differs: $name"; head -20 /tmp/h5diff.$$; status=1
      fi
      # Root attributes other than the creation time must match too.
      for a in $(h5dump -A -H "$f" 2>/dev/null | sed -n 's/^ *ATTRIBUTE "\(.*\)" {/\1/p' | grep -v created_utc); do
        if [ "$(h5dump -a "/$a" "$f" | tail -n +2)" != "$(h5dump -a "/$a" "$g" | tail -n +2)" ]; then
          echo "differs: $name attribute /$a"; status=1
        fi
      done ;;
    *.json)
      if ! diff <(grep -v '"\(wall_s\|simulation_thread_s\|fitting_thread_s\)"' "$f") \
                <(grep -v '"\(wall_s\|simulation_thread_s\|fitting_thread_s\)"' "$g") > /dev/null; then
        echo "differs: $name"; diff <(grep -v '_s"' "$f") <(grep -v '_s"' "$g") | head -10; status=1
      fi ;;
    *)
      if ! cmp -s "$f" "$g"; then echo "differs: $name"; diff "$f" "$g" | head -10; status=1; fi ;;
  esac
done
rm -f /tmp/h5diff.$$
[ $status -eq 0 ] && echo "snapshots agree ($(ls "$old" | wc -l) files)"
exit $status
