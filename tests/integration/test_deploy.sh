#!/bin/sh
# The deployment recipes of deploy/: every Kubernetes manifest parses, is
# a well-formed object, and names only the image deploy/Containerfile
# builds (mpbench:TAG), programs the build installs into bin/ (or the
# hub, java with lcm.jar's TCPService, which the Containerfile installs),
# files that exist in the repository (under /opt/mpbench, where the
# Containerfile copies it), and the hub Service's port in every tcpq://
# URL. The Slurm script parses as sh and runs only mpbench's own programs
# (and the hub), each one the build installs.
set -u
. "$MPB_SOURCE/tests/integration/lib.sh"
if ! python3 -c 'import yaml' 2>/dev/null; then
    echo "skipped: needs python3's yaml module (python3-yaml)"
    echo "0 passed, 0 failed, 1 skipped"
    exit 0
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
D=$MPB_SOURCE/deploy

cmake --install "$MPB_BUILD" --prefix "$work/prefix" >/dev/null 2>&1
check "the build installs" test -x "$work/prefix/bin/mpbenchd"
check "the Containerfile builds from Debian 12" grep -q '^FROM debian:12$' "$D/Containerfile"
check "... copies the repository to /opt/mpbench" grep -q '^COPY \. /opt/mpbench$' "$D/Containerfile"
check "... installs the build, the hub's jar and a Java runtime" \
    sh -c "grep -q 'cmake --install build --prefix /usr/local' '$D/Containerfile' &&
           grep -q liblcm-java '$D/Containerfile' && grep -q 'jre' '$D/Containerfile'"

python3 - "$D" "$work/prefix/bin" "$MPB_SOURCE" >"$work/k8s.out" 2>&1 <<'PY'
import glob, os, sys, yaml
deploy, bindir, source = sys.argv[1:]
installed = set(os.listdir(bindir))
bad, containers, kinds, ports, urls = [], 0, [], set(), []
for path in sorted(glob.glob(os.path.join(deploy, "kubernetes", "*.yaml"))):
    name = os.path.relpath(path, source)
    try:
        docs = [d for d in yaml.safe_load_all(open(path)) if d is not None]
    except yaml.YAMLError as e:
        bad.append(f"{name}: does not parse: {e}")
        continue
    for d in docs:
        for key in ("apiVersion", "kind", "metadata"):
            if key not in d:
                bad.append(f"{name}: a document without {key}")
        kinds.append(d.get("kind"))
        if d.get("kind") == "Service":
            ports |= {p["port"] for p in d["spec"]["ports"]}
        pod = d.get("spec", {}).get("template", {}).get("spec", {})
        for c in pod.get("containers", []) + pod.get("initContainers", []):
            containers += 1
            image = c.get("image", "")
            if not image.startswith("mpbench:"):
                bad.append(f"{name}: image {image!r} is not deploy/Containerfile's mpbench")
            cmd = c.get("command", []) + c.get("args", [])
            if not cmd:
                bad.append(f"{name}: container {c.get('name')} names no command")
                continue
            if cmd[0] == "java":
                if "/usr/share/java/lcm.jar" not in cmd or "lcm.lcm.TCPService" not in cmd:
                    bad.append(f"{name}: java runs something but the hub: {cmd}")
            elif cmd[0] not in installed:
                bad.append(f"{name}: {cmd[0]} is not a program the build installs")
            for a in cmd:
                if a.startswith("/opt/mpbench/") and not os.path.exists(
                        os.path.join(source, a[len("/opt/mpbench/"):])):
                    bad.append(f"{name}: {a} is not in the repository")
                if a.startswith("tcpq://"):
                    urls.append((name, int(a.rsplit(":", 1)[1])))
for name, port in urls:
    if port not in ports:
        bad.append(f"{name}: tcpq:// port {port} is no Service's")
for k in ("Deployment", "Service", "Job", "PersistentVolumeClaim"):
    if k not in kinds:
        bad.append(f"no {k} among the manifests")
print(f"{containers} containers checked")
for b in bad:
    print(b)
sys.exit(1 if bad or containers < 3 else 0)
PY
rc=$?
check "the Kubernetes manifests parse and name only the repo's image, programs and files" eq $rc 0
[ $rc -eq 0 ] || cat "$work/k8s.out"

S=$D/slurm/mpbench.sbatch
check "the Slurm script parses as sh" sh -n "$S"
# Every mpbench program it names ("$bin/NAME"), each installed.
progs=$(grep -o '\$bin/[A-Za-z0-9_-]*' "$S" | sed 's/\$bin\///' | sort -u)
missing=""
for p in $progs; do
    [ -x "$work/prefix/bin/$p" ] || missing="$missing $p"
done
check "the Slurm script's programs ($(echo $progs)) are all installed" \
    test -n "$progs" -a -z "$missing"
# Its other commands: the shell's, Slurm's, and the hub.
others=$(sed -e 's/#.*//' "$S" | grep -v '^\s*$' |
    awk '{print $1}' | grep -v -e '^"\$bin/' -e '=' -e '^-' -e '^\\' \
        -e '^trap$' -e '^set$' -e '^sleep$' -e '^srun$' -e '^java$' \
        -e '^--' -e '^>' -e '^"\$' -e '^hub=' -e '^planners=' -e '^lcm' | sort -u)
check "it runs nothing else (found: $(echo $others))" test -z "$others"
check "its java runs the hub alone" \
    test "$(grep -c '^java ' "$S")" -eq "$(grep -c '^java -Xmx[0-9]*m -cp /usr/share/java/lcm.jar lcm.lcm.TCPService' "$S")"
mpb_finish
