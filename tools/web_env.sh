#!/bin/sh
# web_env.sh - what the HTML views need: three.js, which `mpb view` inlines
# into every page it writes, and for the tests a headless Chromium (Debian's
# chromium) driven by playwright-core. Run by `make deps`.
#
# npm packages are fetched with `npm pack` at exact versions, checked
# against the integrity hashes below (sha512, as the npm registry publishes
# them) and unpacked into .cache/web/node_modules (git-ignored). Nothing
# is fetched from anywhere but the package registries: playwright-core is
# used with executablePath /usr/bin/chromium, never its own browser download.
#
# Idempotent: a package already unpacked at its version is left alone, and
# chromium is installed only when missing.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/tools/usage.sh"
mpb_no_arguments "$@"
cache=$root/.cache/web

# name version integrity
NPM_PACKAGES="
three 0.170.0 sha512-FQK+LEpYc0fBD+J8g6oSEyyNzjp+Q7Ks1C568WWaoMRLW+TkNNWmenWeGgJjV105Gd+p/2ql1ZcjYvNiPZBhuQ==
playwright-core 1.65.1 sha512-hqPpz7blSMPxWVdoeE1yiBSzXsKiVOd2k+kjCvmUywD2GPO2Dd9HfcWnq9NN0GHbNZDFgZ9JfBFr+X5/BLo0qw==
"
# three 0.170.0 is the last release whose build/three.module.min.js is one
# file (0.171 split it into three.module.js and three.core.js), which is
# what lets `mpb view` inline it.

SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
if ! dpkg-query -W -f='${Status}' chromium 2>/dev/null | grep -q 'install ok installed'; then
    echo "deps: installing chromium (Debian)"
    export DEBIAN_FRONTEND=noninteractive
    $SUDO apt-get update -qq
    $SUDO apt-get install -y -qq --no-install-recommends chromium
fi
for tool in node npm; do
    if ! command -v $tool >/dev/null 2>&1; then
        echo "deps: $tool is needed for the view tests (Debian: nodejs npm)" >&2
        exit 1
    fi
done

mkdir -p "$cache/node_modules" "$cache/tarballs"
echo "$NPM_PACKAGES" | while read -r name version integrity; do
    [ -n "$name" ] || continue
    dest=$cache/node_modules/$name
    if [ -f "$dest/package.json" ] &&
       node -e 'process.exit(require(process.argv[1]).version === process.argv[2] ? 0 : 1)' \
            "$dest/package.json" "$version"; then
        echo "deps: $name $version present"
        continue
    fi
    tgz=$cache/tarballs/$name-$version.tgz
    if [ ! -f "$tgz" ]; then
        echo "deps: fetching $name $version from the npm registry"
        (cd "$cache/tarballs" && npm pack --silent "$name@$version" >/dev/null)
    fi
    got=$(node -e 'const c = require("crypto"), fs = require("fs");
        process.stdout.write("sha512-" + c.createHash("sha512")
            .update(fs.readFileSync(process.argv[1])).digest("base64"))' "$tgz")
    if [ "$got" != "$integrity" ]; then
        echo "deps: $tgz: integrity $got, expected $integrity" >&2
        rm -f "$tgz"
        exit 1
    fi
    rm -rf "$dest.tmp" && mkdir -p "$dest.tmp"
    tar xzf "$tgz" -C "$dest.tmp" --strip-components=1
    rm -rf "$dest" && mv "$dest.tmp" "$dest"
    echo "deps: $name $version unpacked into .cache/web"
done
