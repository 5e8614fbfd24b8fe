#!/bin/sh
# tools/microfacet_demo.sh [FOGRT] [SHARED]: CS184's CBspheres with its two spheres made rough
# metals as CS184 writes them (`make microfacet-demo`): the mirror sphere becomes aluminium at
# alpha 0.05, the glass sphere silver at alpha 0.5 (eta and k per channel). The scene is made
# in build/microfacet/ from SHARED's CBspheres.dae (only its two materials change) and rendered
# twice at 480 x 360, 256 spp: clear.png, and fog.png with fog in the room (--density 0.4 --g
# 0.5 --fog-bounds scene). About a minute on 2 cores. docs/figures/microfacet_*.png are these.
set -e
FOGRT=${1:-build/fogrt} SHARED=${2:-../shared}
IN=$SHARED/scenes/cs184/CBspheres.dae
OUT=build/microfacet
if [ ! -f "$IN" ]; then
    echo "microfacet-demo: $IN not found (the CS184 scenes live in SHARED=$SHARED): nothing rendered" >&2
    exit 2
fi
mkdir -p "$OUT"
# The first <mirror> ... </mirror> and <glass> ... </glass> blocks become <microfacet> blocks.
awk '
    /<mirror>/ && !m { print "          <microfacet>"; print "            <alpha>0.05</alpha>";
                       print "            <eta>1.6574599 0.8803689 0.5212287</eta>";
                       print "            <k>9.2238691 6.2695232 4.8370012</k>"; skip = 1; m = 1; next }
    /<glass>/ && !g  { print "          <microfacet>"; print "            <alpha>0.5</alpha>";
                       print "            <eta>0.059881 0.059881 0.047366</eta>";
                       print "            <k>4.0 3.5 2.8</k>"; skip = 1; g = 1; next }
    skip && /<\/(mirror|glass)>/ { print "          </microfacet>"; skip = 0; next }
    !skip { print }
' "$IN" > "$OUT/CBspheres_microfacet.dae"
"$FOGRT" -r 480 360 -s 256 -f "$OUT/clear.png" "$OUT/CBspheres_microfacet.dae"
"$FOGRT" -r 480 360 -s 256 --density 0.4 --g 0.5 --fog-bounds scene -f "$OUT/fog.png" "$OUT/CBspheres_microfacet.dae"
echo "microfacet-demo: wrote $OUT/clear.png and $OUT/fog.png"
