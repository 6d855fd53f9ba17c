#!/usr/bin/env bash
# Writes the real shard parts that fuzz/part_merge.h merges beside each fuzzed part (the fuzz target
# part_merge_fuzz and FuzzCorpus.ShardPartsEndInADocumentedStatus), and copies them into the corpus
# as its seeds: small jobs of every kind that shards, each split in two, written from this
# directory so that a part names its input file as it is here. Run it again when the part format
# changes:  tests/fuzz/parts/make_parts.sh build/vgroove
set -euo pipefail
bin=$(realpath "$1")
cd "$(dirname "$0")"
rm -f ./*.part.json
for s in 1 2; do
  for suite in brdf table2 table1; do
    "$bin" validate "$suite.json" --threads 1 --shard "$s/2" --out "$suite.$s.part.json" >/dev/null
  done
  "$bin" simulate scene.json --threads 1 --shard "$s/2" --out "simulate.$s.part.json" >/dev/null
  "$bin" energy --ndf ggx --dim flatland --mu-points 2 --alpha-points 1 --rays 500 --max-k 3 --threads 1 \
    --shard "$s/2" --out "energy.$s.part.json" >/dev/null
done
corpus=../corpus/part_merge_fuzz
mkdir -p "$corpus"
for p in ./*.part.json; do cp "$p" "$corpus/$(sha1sum "$p" | cut -c1-40)"; done
