#!/usr/bin/env bash
# imgcmp.sh: compare a test image with a reference image (linear EXR, same
# size), with oiiotool for pixels and awk for the arithmetic of the pixel
# and block checks; the error metrics are experiments/analysis/metrics.py's. Modes:
#
#   imgcmp.sh pixel TEST REF [REL [MAXBAD]]
#       Per pixel and channel: bad when |t-r| > REL*r + 1e-4*mean(r)
#       (REL default 1e-3: two half-float rounding steps). Prints the share of
#       bad pixels; fails (exit 1) when it exceeds MAXBAD (default 0.003).
#   imgcmp.sh block TEST REF [BW BH [THRESHOLD]]
#       Box-downsamples both to BW x BH blocks (default 32x24); per block and
#       channel e = |t-r| / (r + 0.01*mean(r)); prints the 99th percentile,
#       the channel-mean ratios t/r and the sRGB 8-bit RMS/PSNR; fails when
#       the percentile exceeds THRESHOLD (default 0.15), or, when
#       IMGCMP_MEAN_TOL=T is set, when a channel-mean ratio is outside 1 +- T.
#   imgcmp.sh stats TEST REF [MASK]
#       Prints relMSE, RMSE and PSNR as experiments/analysis/metrics.py
#       defines them (its docstring), PSNR with peak = the reference's
#       maximum, over all pixels or those where MASK has a non-zero channel.
#
# IMGCMP_CUT=WxH+X+Y (environment) restricts every mode to that window of
# both images (e.g. the caustic's region).
# Exit status: 0 pass, 1 fail, 2 usage or unreadable image.
set -u -o pipefail

die() { echo "imgcmp: $*" >&2; exit 2; }
WORK=$(mktemp -d /tmp/imgcmp.XXXXXX) || die "cannot make a temporary directory"
trap 'rm -rf "$WORK"' EXIT
NDUMP=0

# dump IMAGE [OIIOTOOL-OPS...]: "x y c0 c1 c2" per pixel, first 3 channels,
# after the given oiiotool operations (float precision throughout)
dump() {
  local img=$1; shift
  [ -r "$img" ] || die "$img: cannot read"
  NDUMP=$((NDUMP + 1))
  local tmp="$WORK/d$NDUMP.$BASHPID.exr"
  local cut=()
  [ -n "${IMGCMP_CUT:-}" ] && cut=(--cut "$IMGCMP_CUT" --origin +0+0)
  oiiotool -i "$img" "${cut[@]}" "$@" --ch 0,1,2 -d float -o "$tmp" 2>/dev/null || die "$img: oiiotool failed"
  oiiotool --dumpdata "$tmp" | awk '/^ *Pixel/ { gsub(/[(),:]/, " "); print $2, $3, $4, $5, $6 }'
}

# size IMAGE: "W H"
size() { oiiotool --info "$1" 2>/dev/null | awk '{ for (i = 1; i < NF; i++) if ($(i + 1) == "x") { print $i, $(i + 2); exit } }' | tr -d ','; }

mode=${1:-}; shift || true
[ $# -ge 2 ] || die "usage: imgcmp.sh pixel|block|stats TEST REF [...]"
test_img=$1 ref_img=$2; shift 2
st=$(size "$test_img") || die "$test_img: cannot read"
sr=$(size "$ref_img") || die "$ref_img: cannot read"
[ -n "$st" ] && [ "$st" = "$sr" ] || die "sizes differ: $test_img ($st) vs $ref_img ($sr)"

case "$mode" in
pixel)
  rel=${1:-1e-3} maxbad=${2:-0.003}
  paste -d' ' <(dump "$test_img") <(dump "$ref_img") | awk -v rel="$rel" -v maxbad="$maxbad" '
    { n++; for (c = 0; c < 3; c++) { t[n, c] = $(3 + c); r[n, c] = $(8 + c); sum[c] += $(8 + c) } }
    END {
      if (n == 0) { print "no pixels"; exit 2 }
      for (c = 0; c < 3; c++) floor_[c] = 1e-4 * sum[c] / n
      for (i = 1; i <= n; i++) {
        b = 0
        for (c = 0; c < 3; c++) {
          d = t[i, c] - r[i, c]; if (d < 0) d = -d
          e = d / (r[i, c] + floor_[c]); if (e > worst) worst = e
          if (d > rel * r[i, c] + floor_[c]) b = 1
        }
        bad += b
      }
      share = bad / n
      printf "pixel: %d of %d pixels (%.4f%%) differ by more than %g relative; worst %.3g\n", bad, n, 100 * share, rel, worst
      exit share > maxbad ? 1 : 0
    }'
  ;;
block)
  bw=${1:-32} bh=${2:-24} thr=${3:-0.15}
  paste -d' ' <(dump "$test_img" --resize:filter=box "${bw}x${bh}") <(dump "$ref_img" --resize:filter=box "${bw}x${bh}") |
    awk -v thr="$thr" -v mtol="${IMGCMP_MEAN_TOL:-}" '
    { n++; for (c = 0; c < 3; c++) { t[n, c] = $(3 + c); r[n, c] = $(8 + c); st[c] += $(3 + c); sr[c] += $(8 + c) } }
    function srgb(x) { if (x <= 0) return 0; if (x >= 1) return 255; x = (x <= 0.0031308) ? 12.92 * x : 1.055 * x ^ (1 / 2.4) - 0.055; return int(x * 255 + 0.5) }
    END {
      if (n == 0) { print "no blocks"; exit 2 }
      m = 0
      for (i = 1; i <= n; i++) for (c = 0; c < 3; c++) {
        d = t[i, c] - r[i, c]; if (d < 0) d = -d
        e[++m] = d / (r[i, c] + 0.01 * sr[c] / n)
        q = srgb(t[i, c]) - srgb(r[i, c]); se += q * q
      }
      # sort the m block errors (insertion sort is fine for a few thousand)
      for (i = 2; i <= m; i++) { v = e[i]; j = i - 1; while (j > 0 && e[j] > v) { e[j + 1] = e[j]; j-- } e[j + 1] = v }
      k = int(0.99 * m + 0.999999); if (k < 1) k = 1; if (k > m) k = m
      p99 = e[k]; rms = sqrt(se / m); psnr = rms > 0 ? 20 * log(255 / rms) / log(10) : 99
      printf "block: p99 %.4f (threshold %g) over %d blocks; channel means t/r %.4f %.4f %.4f%s; sRGB8 RMS %.2f PSNR %.1f dB\n",
        p99, thr, n, st[0] / sr[0], st[1] / sr[1], st[2] / sr[2], mtol != "" ? sprintf(" (tolerance %g)", mtol) : "", rms, psnr
      bad = p99 > thr
      if (mtol != "") for (c = 0; c < 3; c++) { q = st[c] / sr[c] - 1; if (q < 0) q = -q; if (q > mtol + 0) bad = 1 }
      exit bad ? 1 : 0
    }'
  ;;
stats)
  # the metrics of experiments/analysis/metrics.py (their one definition),
  # PSNR with the reference's peak; on the IMGCMP_CUT window if set
  mask=${1:-}
  if [ -n "$mask" ]; then [ "$(size "$mask")" = "$st" ] || die "mask size differs: $mask"; fi
  cut() { # IMAGE -> a float copy (of the window) in WORK
    local out="$WORK/s$NDUMP.$RANDOM.exr" c=(); NDUMP=$((NDUMP + 1))
    [ -n "${IMGCMP_CUT:-}" ] && c=(--cut "$IMGCMP_CUT" --origin +0+0)
    oiiotool -i "$1" "${c[@]}" -d float -o "$out" 2>/dev/null || die "$1: oiiotool failed"
    echo "$out"
  }
  args=("$(cut "$test_img")" "$(cut "$ref_img")" --peak max --csv)
  [ -n "$mask" ] && args+=(--mask "$(cut "$mask")")
  line=$(cd "$(dirname "$0")/.." && "${PYTHON:-/usr/bin/python3}" -m experiments.analysis.metrics "${args[@]}") || exit 2
  IFS=, read -r rel rmse psnr n _ <<< "$line"
  printf 'stats: pixels %d relMSE %s RMSE %s PSNR %.2f dB\n' "$n" "$rel" "$rmse" "$psnr"
  ;;
*) die "unknown mode '$mode' (pixel, block or stats)" ;;
esac
