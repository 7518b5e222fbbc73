#!/usr/bin/env bash
# Same bytes on every instruction set (docs/architecture.md, Contracts): the vector loops are cloned
# for x86-64-v4, AVX2 and the baseline, and their files are built with -ffp-contract=off so that no
# clone fuses a*b + c into one rounding where FMA exists and the baseline does not. GCC 12 was
# found to fuse anyway in one pattern (a scalar add/subtract pair after SLP vectorisation became
# vfmaddsub; docs/architecture.md), so this checks the compiled libraries themselves: no fused
# multiply-add instruction (vfmadd, vfmsub, vfnmadd, vfnmsub, vfmaddsub, vfmsubadd, any width) may
# appear in them. The project calls no fma() of its own.
# Usage: no_fused_multiply_add.sh LIBRARY_OR_OBJECT...
set -u
found=0
if [[ $# -eq 0 ]]; then
  echo "FAIL: no library given" >&2
  exit 2
fi
for file in "$@"; do
  # A disassembly that failed or holds no instruction would pass vacuously: both are failures.
  if ! listing=$(objdump -d --no-show-raw-insn "$file"); then
    echo "FAIL: objdump could not disassemble $file"
    exit 2
  fi
  if ! grep -qE '^\s*[0-9a-f]+:\s+[a-z]' <<<"$listing"; then
    echo "FAIL: no instruction found in the disassembly of $file"
    exit 2
  fi
  hits=$(grep -E '^\s*[0-9a-f]+:\s+vfn?m(add|sub)' <<<"$listing" || true)
  if [[ -n $hits ]]; then
    echo "FAIL: $(basename "$file") holds $(wc -l <<<"$hits") fused multiply-add instruction(s), e.g.:"
    head -3 <<<"$hits"
    found=1
  fi
done
if [[ $found -eq 0 ]]; then
  echo "no fused multiply-add instruction in $# libraries"
fi
exit $found
