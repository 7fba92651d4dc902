#!/usr/bin/env bash
# Compares two snapshots of scripts/behaviour_snapshot.sh. HDF5 files: every dataset and
# attribute within 1e-12 relative (h5diff -p, from Debian's hdf5-tools), except the creation
# time. Text and JSON: identical, except the diagnosis' timing fields (wall and thread seconds).
# Prints one line per difference; exit 1 if any.
set -uo pipefail
old=$1
new=$2
status=0
# The diagnosis JSON with its timing values (not its simulation count) blanked.
untimed() { sed -E 's/"(wall_s|simulation_thread_s|fitting_thread_s)": [-+0-9.eE]+/"\1": _/g' "$1"; }
headers() { h5dump -A "$1" | sed -e 1d -e '/[0-9]\{4\}-[0-9][0-9]-[0-9][0-9]T[0-9:]*Z/d'; }
for f in "$old"/*; do
  name=$(basename "$f")
  g="$new/$name"
  if [ ! -e "$g" ]; then echo "missing: $name"; status=1; continue; fi
  case "$name" in
    *.h5)
      if ! h5diff -p 1e-12 --exclude-attribute / "$f" "$g" > /tmp/h5diff.$$ 2>&1; then
        echo "differs: $name"; head -20 /tmp/h5diff.$$; status=1
      fi
      # Structure and every attribute (h5dump -A: header and attributes, no data), except the
      # file name and the creation time.
      if ! diff <(headers "$f") <(headers "$g") > /dev/null; then
        echo "differs: $name (structure or attributes)"; diff <(headers "$f") <(headers "$g") | head -10; status=1
      fi ;;
    *.json)
      if ! diff <(untimed "$f") <(untimed "$g") > /dev/null; then
        echo "differs: $name"; diff <(untimed "$f") <(untimed "$g") | head -10; status=1
      fi ;;
    *)
      if ! cmp -s "$f" "$g"; then echo "differs: $name"; diff "$f" "$g" | head -10; status=1; fi ;;
  esac
done
rm -f /tmp/h5diff.$$
[ $status -eq 0 ] && echo "snapshots agree ($(ls "$old" | wc -l) files)"
exit $status
