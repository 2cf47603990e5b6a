#!/usr/bin/env bash
# Runs the usage commands README.md shows (the sh block after the marker
# `<!-- readme-commands -->`) exactly as written, against the build in
# build/, so that what a new user copies works. Their output goes to a log,
# printed when a command fails.
set -euo pipefail
cd "$(dirname "$0")/.."
commands=$(awk '/<!-- readme-commands -->/ { marked = 1; next }
                marked && /^```sh/ { inside = 1; next }
                inside && /^```/ { exit }
                inside { print }' README.md)
if [ -z "$commands" ]; then
  echo "check_readme_commands: README.md has no sh block after <!-- readme-commands -->" >&2
  exit 1
fi
rm -rf /tmp/l2s_readme  # where the README's commands write
log=$(mktemp)
if ! bash -euo pipefail -x -c "$commands" >"$log" 2>&1; then
  echo "check_readme_commands: a README command failed:" >&2
  tail -n 30 "$log" >&2
  exit 1
fi
echo "check_readme_commands: $(grep -c . <<<"$commands") README commands ran"
