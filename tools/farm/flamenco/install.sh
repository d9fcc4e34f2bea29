#!/usr/bin/env bash
# Installs Flamenco's Manager and Worker (GPL-3.0, built from the Go module
# proxy; never vendored here) into $FLAMENCO_BIN. Idempotent: does nothing
# when both binaries are already there. Exit 0 on success, 3 when the module
# proxy refuses Flamenco's module (nothing to retry), 1 on other failures.
#   FLAMENCO_BIN      where the binaries go (default ~/.cache/banyan/flamenco/bin)
#   FLAMENCO_VERSION  module version (default main; release tags are not Go
#                     versions, so use main or a commit hash)
#   GO                the go tool (default: go on PATH, else /usr/local/go/bin/go)
set -euo pipefail
BIN=${FLAMENCO_BIN:-$HOME/.cache/banyan/flamenco/bin}
VER=${FLAMENCO_VERSION:-main}
if [[ -x $BIN/flamenco-manager && -x $BIN/flamenco-worker ]]; then
    echo "flamenco: already installed in $BIN"
    exit 0
fi
GO=${GO:-$(command -v go || echo /usr/local/go/bin/go)}
if [[ ! -x $GO ]]; then
    echo "flamenco: no Go toolchain (need Go >= 1.26 for flamenco@main)" >&2
    exit 1
fi
mkdir -p "$BIN"
# -p 2: the build machines have 2 cores shared with other jobs.
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for cmd in flamenco-manager flamenco-worker; do
    echo "flamenco: go install .../cmd/$cmd@$VER -> $BIN"
    if ! GOBIN=$BIN GOFLAGS="${GOFLAGS:-} -p=2" "$GO" install \
            "projects.blender.org/studio/flamenco/cmd/$cmd@$VER" >"$log" 2>&1; then
        cat "$log" >&2
        if grep -qiE "403|not permitted|allowlist" "$log"; then
            # The proxy answered no: retrying will not help (exit 3).
            echo "flamenco: the Go module proxy refused Flamenco's module; it cannot be installed on this machine" >&2
            exit 3
        fi
        exit 1
    fi
done
"$BIN/flamenco-manager" -version 2>/dev/null | head -1 || true
