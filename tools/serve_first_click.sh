#!/bin/bash
# The web app's first click (at the centre of a camera) with and without views built ahead (POST /api/focus), measured
# through the HTTP API on a fresh embedding cache each time.
#   tools/serve_first_click.sh SCENE CAMERA [serve options...]
# e.g. tools/serve_first_click.sh ../shared/fixtures/dtu24/scene 30 --views auto:10
set -euo pipefail
scene=$1; cam=$2; shift 2
bin=${ISEGMAN:-build/isegman}
port=${PORT:-8791}
url=http://127.0.0.1:$port
work=$(mktemp -d)
trap 'kill $pid 2>/dev/null || true; rm -rf "$work"' EXIT
now() { date +%s.%N; }
json() { python3 -c "import json,sys; d=json.load(sys.stdin); print($1)"; }

for mode in without with; do
  "$bin" serve "$scene" --host 127.0.0.1 --port "$port" --out-dir "$work/out" --cache "$work/cache-$mode" "$@" \
    > "$work/serve-$mode.log" 2>&1 &
  pid=$!
  until curl -sf "$url/api/status" 2>/dev/null | grep -q '"state":"ready"'; do
    kill -0 $pid 2>/dev/null || { cat "$work/serve-$mode.log"; exit 1; }
    sleep 0.5
  done
  while curl -sf "$url/api/status" | grep -q '"busy":true'; do sleep 0.5; done
  read -r cx cy < <(curl -sf "$url/api/scene" | json "'%s %s' % (d['cameras'][$cam]['width'] / 2, d['cameras'][$cam]['height'] / 2)")
  if [ "$mode" = with ]; then
    t0=$(now)
    curl -sf -X POST -d "{\"view\": $cam}" "$url/api/focus" > /dev/null
    until curl -sf "$url/api/status" | grep -q "ahead for a click in camera $cam"; do sleep 0.2; done
    echo "views built ahead for camera $cam in $(echo "$(now) - $t0" | bc) s"
  fi
  t0=$(now)
  job=$(curl -sf -X POST -d "{\"view\": $cam, \"x\": $cx, \"y\": $cy, \"label\": 1}" "$url/api/click" | json "d['job']")
  until curl -sf "$url/api/jobs/$job" | grep -q '"state":"\(done\|failed\)"'; do sleep 0.05; done
  echo "$mode views built ahead: first click $(echo "$(now) - $t0" | bc) s;" \
    "$(curl -sf "$url/api/status" | json "str(d['edit']['selected']) + ' selected, views ' + str([v['camera'] for v in d['segmentation']['views']])")"
  kill $pid; wait $pid 2>/dev/null || true
done
