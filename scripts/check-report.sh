#!/usr/bin/env bash
# Checks `cargo xtask report` in a real browser.
#
#   scripts/check-report.sh install   install Debian's chromium if /usr/bin/chromium is missing
#   scripts/check-report.sh [DIR]     install it if needed, then: run fig2 and fig3 (cheap, with
#                                     SVG figures) into DIR (default: a new temporary directory),
#                                     write DIR/index.html, screenshot it headless into
#                                     DIR/report.png, and check page and screenshot with the
#                                     integration test xtask/tests/report.rs (REPORT_CHECK_OUT=DIR)
#
# The same checks run in `cargo test` (the test makes its own directory); with CI=true a missing
# Chromium fails that test, so .ci/run calls `install` first.
set -euo pipefail
cd "$(dirname "$0")/.."

CHROMIUM="${CHROMIUM:-/usr/bin/chromium}"

install_chromium() {
    if [ -x "$CHROMIUM" ]; then
        return 0
    fi
    local sudo=()
    if [ "$(id -u)" -ne 0 ]; then
        sudo=(sudo)
    fi
    echo "check-report: installing Debian's chromium" >&2
    "${sudo[@]}" apt-get update
    "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive \
        apt-get install -y --no-install-recommends chromium
    [ -x "$CHROMIUM" ] || { echo "check-report: $CHROMIUM still missing after install" >&2; exit 1; }
}

screenshot() {
    local out="$1"
    "$CHROMIUM" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
        --disable-background-networking --disable-component-update --disable-sync \
        --hide-scrollbars --window-size=1280,4000 \
        --user-data-dir="$out/.chromium-profile" \
        --screenshot="$out/report.png" "file://$out/index.html" \
        >/dev/null 2>"$out/chromium.log"
}

main() {
    if [ "${1:-}" = "install" ]; then
        install_chromium
        return 0
    fi
    install_chromium
    local out="${1:-$(mktemp -d "${TMPDIR:-/tmp}/check-report.XXXXXX")}"
    mkdir -p "$out"
    out="$(cd "$out" && pwd)"
    cargo xtask run fig2 fig3 --threads 1 --out "$out" >/dev/null
    cargo xtask report --out "$out"
    screenshot "$out"
    REPORT_CHECK_OUT="$out" cargo test --release --quiet -p xtask --test report \
        report_page_shows_every_experiment_and_its_figures
    echo "check-report: ok: $out/index.html, $out/report.png"
}

main "$@"
