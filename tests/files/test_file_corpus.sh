#!/usr/bin/env bash
# ctest's files.EdgeCaseCorpus: makes the corpus in a fresh directory, then checks it.
# Usage: test_file_corpus.sh GENERATOR STATMC
set -euo pipefail
dir=$(mktemp -d "${TMPDIR:-/tmp}/statmc-corpus.XXXXXX")
trap 'rm -rf "$dir"' EXIT
"$1" "$dir"
"$(dirname "$0")/check_files.sh" "$2" "$dir"
