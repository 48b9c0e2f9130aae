#!/usr/bin/python3
"""Offline checks of deploy/: the Dockerfile, docker-compose.yml and deploy/k8s/.

No container engine or cluster is needed. Every container of the compose file and of the
Kubernetes manifests is *run* here as a process on 127.0.0.1, with its own command and args: the
paths it mounts are mapped to temporary directories (a ConfigMap's files written out, a named
volume or emptyDir an empty directory), --listen becomes 127.0.0.1:0, and the host names in
--servers become the addresses of the servers started for those services. So every flag is one
the binary accepts with that value, the bake fills the store the servers then map, and the batch
jobs render over the servers they name. Besides:

  * the YAML parses; references resolve (Service selector -> Deployment, HPA -> Deployment,
    ConfigMap and PVC names, image = the tag deploy/Dockerfile builds);
  * probe ports, containerPort, Service targetPort, published ports, the Dockerfile's EXPOSE and
    HEALTHCHECK all match the server's --listen port;
  * grace: terminationGracePeriodSeconds > preStop pause + --grace-s, compose stop_grace_period
    > --grace-s; the store is under an emptyDir of medium Memory (tmpfs volume) at /dev/shm;
  * the Indexed Job's completions = N of --shard $(SHARD)/N, SHARD = the completion index;
  * the Dockerfile's build stage installs scripts/debian-packages.txt and nothing else, and its
    runtime stage installs exactly the Debian packages of the libraries the built binaries link
    (readelf -d NEEDED, dpkg -S), so neither list can drift.

usage: manifests_test.py --repo ROOT --server BIN --client BIN --tex BIN --render BIN
"""

import argparse
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time

try:
    import yaml
except ImportError:  # Debian's python3-yaml, in scripts/debian-packages.txt
    print("FAIL: PyYAML missing: apt-get install python3-yaml (scripts/debian-packages.txt)")
    sys.exit(1)

IMAGE = "aperture:latest"  # the tag docs/DEPLOY.md and deploy/Dockerfile build
ABSL_BINARIES = ("aperture-server", "aperture", "aperture-render")

errors = []
notes = []


def check(condition, message):
    if not condition:
        errors.append(message)
    return condition


def note(message):
    notes.append(message)
    print(message, flush=True)


# --- What the binaries accept ------------------------------------------------------------------


class AbslFlags:
    """Flag names (underscored) and which are booleans, from `BIN --helpfull`."""

    def __init__(self, binary):
        out = subprocess.run([binary, "--helpfull"], capture_output=True, text=True, timeout=30)
        text = out.stdout + out.stderr
        self.usage = text
        self.flags = {}
        # One entry per flag: "  --name (description); default: value;" over one or more lines.
        starts = list(re.finditer(r"^\s+--(\w+) \(", text, re.M))
        for m, end in zip(starts, starts[1:] + [None]):
            entry = text[m.start():end.start() if end else len(text)]
            self.flags[m.group(1)] = bool(re.search(r"\);\s+default: (true|false);", entry))
        check(len(self.flags) > 3, f"{binary} --helpfull listed no flags")

    def parse(self, args, where):
        """Splits args into flags and positionals; reports unknown flags and missing values."""
        positional, i = [], 0
        while i < len(args):
            a = args[i]
            if a.startswith("-") and a not in ("-", "--"):
                body = a.lstrip("-")
                name, has_value = body.split("=", 1)[0].replace("-", "_"), "=" in body
                bool_name = name[2:] if name.startswith("no") and name[2:] in self.flags else name
                if check(name in self.flags or bool_name in self.flags,
                         f"{where}: unknown flag {a}"):
                    if not self.flags.get(bool_name, False) and not has_value:
                        check(i + 1 < len(args), f"{where}: {a} lacks its value")
                        i += 1
            else:
                positional.append(a)
            i += 1
        return positional


class TexCommands:
    """aperture-tex's commands and each one's flags, from its --help texts."""

    def __init__(self, binary):
        out = subprocess.run([binary, "--help"], capture_output=True, text=True, timeout=30)
        self.commands = re.findall(r"^\s{2}([a-z][a-z-]+)\s{2,}", out.stdout + out.stderr, re.M)
        check("bake" in self.commands, f"aperture-tex --help lists no bake: {self.commands}")
        self.binary = binary

    def flags(self, command):
        out = subprocess.run([self.binary, command, "--help"], capture_output=True, text=True,
                             timeout=30)
        usage = (out.stdout + out.stderr).splitlines()[0]
        return dict(re.findall(r"(--[a-z][a-z0-9_-]*)(?: ([A-Z]+))?", usage))


# --- Running containers as processes -----------------------------------------------------------


class Processes:
    def __init__(self):
        self.running = []

    def start_server(self, binary, args, where):
        """Starts aperture-server with args (already mapped); returns its address."""
        out = tempfile.NamedTemporaryFile("w+", delete=False)
        err = tempfile.NamedTemporaryFile("w+", delete=False)
        p = subprocess.Popen([binary] + args, stdout=out, stderr=err)
        self.running.append((p, out.name, err.name))
        for _ in range(300):
            with open(out.name) as f:
                m = re.search(r"^listening on (\S+)", f.read(), re.M)
            if m:
                return p, m.group(1)
            if p.poll() is not None:
                break
            time.sleep(0.1)
        with open(err.name) as f:
            check(False, f"{where}: the server did not start with {args}: {f.read()[-2000:]}")
        return p, None

    def stop(self, p, where, grace_s):
        p.send_signal(signal.SIGTERM)
        try:
            check(p.wait(timeout=grace_s + 10) == 0, f"{where}: the server's exit after SIGTERM "
                  f"is {p.returncode}, not 0")
        except subprocess.TimeoutExpired:
            check(False, f"{where}: the server did not stop within --grace-s + 10 s")

    def cleanup(self):
        for p, out, err in self.running:
            if p.poll() is None:
                p.kill()
                p.wait()
            for f in (out, err):
                os.unlink(f)


def run(argv, where, timeout=120):
    try:
        return subprocess.run(argv, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        check(False, f"{where}: {shlex.join(argv)} did not end within {timeout} s")
        return None


def flag_value(args, name):
    """The value of --name (dash or underscore spelling, '--x v' or '--x=v') in args, or None."""
    want = name.replace("_", "-")
    for i, a in enumerate(args):
        if not a.startswith("-"):
            continue
        body = a.lstrip("-")
        key = body.split("=", 1)[0].replace("_", "-")
        if key == want:
            return body.split("=", 1)[1] if "=" in body else (args[i + 1] if i + 1 < len(args)
                                                               else None)
    return None


def set_flag(args, name, value):
    out, i, want = [], 0, name.replace("_", "-")
    while i < len(args):
        a = args[i]
        body = a.lstrip("-")
        if a.startswith("-") and body.split("=", 1)[0].replace("_", "-") == want:
            out += [a.split("=", 1)[0] + "=" + value] if "=" in body else [a, value]
            i += 1 if "=" in body else 2
            continue
        out.append(a)
        i += 1
    return out


def map_paths(args, mounts):
    """Rewrites container paths under a mount point to the host directory standing for it."""
    def one(text):
        for mount in sorted(mounts, key=len, reverse=True):
            if text == mount or text.startswith(mount.rstrip("/") + "/"):
                return mounts[mount] + text[len(mount.rstrip("/")):]
        return text
    out = []
    for a in args:
        if a.startswith("-") and "=" in a:
            k, v = a.split("=", 1)
            out.append(k + "=" + one(v))
        else:
            out.append(one(a))
    return out


def map_servers(value, addresses, where):
    """--servers NAME:PORT,... -> the local addresses of the servers standing for NAME:PORT."""
    mapped = []
    for entry in value.split(","):
        check(entry in addresses, f"{where}: --servers names {entry}, which is no server here "
              f"(known: {sorted(addresses)})")
        mapped += addresses.get(entry, [])
    return ",".join(mapped)


# --- The Dockerfile ----------------------------------------------------------------------------


def dockerfile_stages(path):
    """[(stage name, [(INSTRUCTION, text)])] with continuation lines joined."""
    stages, lines, current = [], [], ""
    with open(path) as f:
        for raw in f:
            line = raw.rstrip("\n")
            if line.lstrip().startswith("#") and not current:
                continue
            if line.endswith("\\"):
                current += line[:-1] + " "
                continue
            current += line
            if current.strip():
                lines.append(current.strip())
            current = ""
    for line in lines:
        instruction, _, rest = line.partition(" ")
        instruction = instruction.upper()
        if instruction == "FROM":
            m = re.match(r"(\S+)(?:\s+AS\s+(\S+))?", rest, re.I)
            stages.append((m.group(2) or m.group(1), m.group(1), []))
        elif stages:
            stages[-1][2].append((instruction, rest.strip()))
    return stages


def exec_form(text):
    text = text.strip()
    if text.startswith("["):
        return yaml.safe_load(text)
    return shlex.split(text)


def debian_packages(repo):
    with open(os.path.join(repo, "scripts/debian-packages.txt")) as f:
        return [ln.strip() for ln in f if ln.strip() and not ln.strip().startswith("#")]


def runtime_packages_of(binaries):
    """Debian packages owning the libraries the binaries link directly (readelf -d NEEDED)."""
    needed = set()
    for b in binaries:
        out = subprocess.run(["readelf", "-d", b], capture_output=True, text=True, check=True)
        needed |= set(re.findall(r"\(NEEDED\)\s+Shared library: \[(.+?)\]", out.stdout))
    cache = subprocess.run(["/sbin/ldconfig", "-p"], capture_output=True, text=True).stdout
    packages = {}
    for lib in sorted(needed):
        m = re.search(r"^\s+" + re.escape(lib) + r" \(libc6,x86-64\) => (\S+)$", cache, re.M) or \
            re.search(r"^\s+" + re.escape(lib) + r" \(.*?\) => (\S+)$", cache, re.M)
        if not check(m, f"library {lib} not found by ldconfig"):
            continue
        real = os.path.realpath(m.group(1))
        candidates = [real, m.group(1)]
        for c in list(candidates):  # /usr-merged paths: dpkg may know either spelling
            candidates.append(c[4:] if c.startswith("/usr/") else "/usr" + c)
        owner = None
        for c in candidates:
            out = subprocess.run(["dpkg", "-S", c], capture_output=True, text=True)
            if out.returncode == 0:
                owner = out.stdout.split(":")[0].strip()
                break
        if check(owner, f"no Debian package owns {real} ({lib})"):
            packages[lib] = owner
    return packages


def install_runtime_component(build):
    """What the build stage's `cmake --install build --component runtime` puts in bin/: installed
    here from the test's own build folder into a temporary prefix."""
    with tempfile.TemporaryDirectory() as prefix:
        out = subprocess.run(["cmake", "--install", build, "--component", "runtime", "--prefix",
                              prefix], capture_output=True, text=True)
        check(out.returncode == 0, f"cmake --install --component runtime: {out.stderr}")
        installed = sorted(os.listdir(os.path.join(prefix, "bin"))) if out.returncode == 0 else []
    for b in ("aperture-server", "aperture", "aperture-tex", "aperture-render"):
        check(b in installed, f"the runtime component does not install {b} (bin/: {installed})")
    return installed


def check_dockerfile(repo, bins):
    path = os.path.join(repo, "deploy/Dockerfile")
    stages = dockerfile_stages(path)
    check(len(stages) >= 2, "deploy/Dockerfile is not multi-stage")
    names = [s[0] for s in stages]
    check("build" in names and "runtime" in names,
          f"Dockerfile stages {names}: want build, runtime")
    result = {}
    for name, base, steps in stages:
        check(base.startswith("debian:bookworm"), f"Dockerfile stage {name} is FROM {base}, not "
              "Debian bookworm")
        installs = [t for i, t in steps if i == "RUN" and "apt-get install" in t]
        if name == "build":
            copies = [t for i, t in steps if i == "COPY" and "debian-packages.txt" in t]
            check(copies and copies[0].split()[0] == "scripts/debian-packages.txt",
                  "the build stage does not COPY scripts/debian-packages.txt")
            target = copies[0].split()[-1] if copies else "?"
            check(len(installs) == 1, f"the build stage has {len(installs)} apt-get installs, want "
                  "exactly one, from the package list")
            for t in installs:
                m = re.search(r"grep -vE '\^\\s\*\(#\|\$\)' (\S+)\s*\|\s*xargs apt-get install"
                              r" -y -q --no-install-recommends\s*(?:&&|$)", t)
                check(m and m.group(1) == target,
                      "the build stage must install exactly the packages of "
                      f"scripts/debian-packages.txt (grep ... {target} | xargs apt-get install): "
                      f"{t}")
            # The same filter as scripts/install-deps.sh, so both read the same list.
            with open(os.path.join(repo, "scripts/install-deps.sh")) as f:
                check("grep -vE '^\\s*(#|$)' scripts/debian-packages.txt" in f.read(),
                      "scripts/install-deps.sh no longer reads scripts/debian-packages.txt with "
                      "the Dockerfile's filter")
        if name == "runtime":
            check(len(installs) == 1, "the runtime stage must have one apt-get install")
            listed = set()
            for t in installs:
                words = t.split("apt-get install", 1)[1].split("&&")[0].split()
                listed |= {w for w in words if not w.startswith("-")}
            wanted = runtime_packages_of(list(bins.values()))
            essential = {"libc6", "libgcc-s1"}  # in every Debian image
            want = set(wanted.values()) - essential
            check(listed == want, "the runtime stage's packages drifted from what the binaries "
                  f"link: missing {sorted(want - listed)}, not needed {sorted(listed - want)}")
            note(f"Dockerfile runtime packages = Debian packages of the binaries' NEEDED "
                 f"libraries: {len(listed)} ({' '.join(sorted(listed))})")
            users = [t for i, t in steps if i == "USER"]
            check(users and users[-1].split(":")[0] not in ("0", "root"),
                  "the runtime stage does not run as a non-root USER")
            # The binaries arrive as CMake installed them (component runtime) in the build stage.
            copied = [t for i, t in steps if i == "COPY"]
            check(any(re.fullmatch(r"--from=build\s+/staging/usr/local/\s+/usr/local/", t)
                      for t in copied),
                  f"the runtime stage does not copy the build stage's install tree: {copied}")
            # The build folder of the binaries under test (BUILD/server/aperture-server).
            build = os.path.dirname(os.path.dirname(bins["aperture-server"]))
            result["installed"] = install_runtime_component(build)
            result["entrypoint"] = exec_form([t for i, t in steps if i == "ENTRYPOINT"][-1])
            result["cmd"] = exec_form([t for i, t in steps if i == "CMD"][-1])
            result["expose"] = [int(p.split("/")[0]) for i, t in steps if i == "EXPOSE"
                                for p in t.split()]
            hc = [t for i, t in steps if i == "HEALTHCHECK"]
            check(hc, "no HEALTHCHECK")
            if hc:
                result["healthcheck"] = exec_form(hc[-1].split("CMD", 1)[1])
    return result


# --- Compose and Kubernetes --------------------------------------------------------------------


def check_grace(where, args, stop_s, pre_stop_s=0):
    grace = float(flag_value(args, "grace_s") or 10)
    check(stop_s > grace + pre_stop_s,
          f"{where}: {stop_s} s to stop is not more than the preStop pause {pre_stop_s} s + "
          f"--grace-s {grace} s")
    return grace


def seconds(text):
    m = re.fullmatch(r"(\d+(?:\.\d+)?)(ms|s|m|h)?", str(text))
    scale = {"ms": 0.001, "s": 1, "m": 60, "h": 3600, None: 1}[m.group(2)]
    return float(m.group(1)) * scale


def listen_port(args, where):
    listen = flag_value(args, "listen")
    check(listen, f"{where}: no --listen")
    host, _, port = (listen or ":0").rpartition(":")
    check(host == "0.0.0.0", f"{where}: --listen {listen} is not reachable from outside the "
          "container (0.0.0.0)")
    return int(port)


class Runner:
    """Runs containers' commands as local processes (see the module's docstring)."""

    def __init__(self, bins, absl, tex, procs, tmp, store):
        self.bins, self.absl, self.tex, self.procs, self.tmp = bins, absl, tex, procs, tmp
        self.store = store  # one store for every "machine": bake fills it, servers map it

    def binary(self, argv0, where):
        name = os.path.basename(argv0)
        check(name in self.bins, f"{where}: {argv0} is not one of the image's binaries "
              f"{sorted(self.bins)}")
        return name

    def validate(self, name, args, where):
        if name in ABSL_BINARIES:
            positional = self.absl[name].parse(args, where)
            if name == "aperture":
                commands = re.findall(r"^\s+aperture (\w+)", self.absl[name].usage, re.M)
                check(positional and positional[0] in commands,
                      f"{where}: aperture command {positional[:1]} not in {sorted(set(commands))}")
            elif name == "aperture-server":
                check(not positional, f"{where}: aperture-server takes no arguments: {positional}")
        else:  # aperture-tex COMMAND ...
            check(args and args[0] in self.tex.commands,
                  f"{where}: aperture-tex command {args[:1]} not in {self.tex.commands}")
            if args and args[0] in self.tex.commands:
                known = self.tex.flags(args[0])
                i = 1
                while i < len(args):
                    if args[i].startswith("--"):
                        flag = args[i].split("=", 1)[0]
                        check(flag in known, f"{where}: aperture-tex {args[0]} has no {flag} "
                              f"(usage: {sorted(known)})")
                        if known.get(flag) and "=" not in args[i]:
                            i += 1
                    i += 1

    def start_server(self, args, mounts, where):
        args = map_paths(args, mounts)
        args = set_flag(args, "listen", "127.0.0.1:0")
        check(flag_value(args, "store") not in (None, "none"), f"{where}: the server has no store")
        args = set_flag(args, "store", self.store)
        p, address = self.procs.start_server(self.bins["aperture-server"], args, where)
        return p, address, args

    def run_tool(self, name, args, mounts, where, want_rc=0, want_text=None):
        args = map_paths(args, mounts)
        if name == "aperture-tex" and flag_value(args, "store"):
            args = set_flag(args, "store", self.store)
        r = run([self.bins[name]] + args, where, timeout=300)
        if r is None:
            return None
        check(r.returncode == want_rc, f"{where}: {name} {shlex.join(args)} exited "
              f"{r.returncode}, want {want_rc}: {(r.stdout + r.stderr)[-1500:]}")
        if want_text:
            check(want_text in r.stdout + r.stderr, f"{where}: no '{want_text}' in "
                  f"{(r.stdout + r.stderr)[-1500:]}")
        return r


def check_compose(repo, runner, docker):
    path = os.path.join(repo, "deploy/docker-compose.yml")
    with open(path) as f:
        compose = yaml.safe_load(f)
    services = compose["services"]
    for name in ("bake", "server-a", "server-b", "batch"):
        check(name in services, f"compose: no service {name}")
    shm = compose.get("volumes", {}).get("shm", {})
    check(shm.get("driver_opts", {}).get("type") == "tmpfs",
          "compose: the store volume 'shm' is not a tmpfs")
    base = os.path.dirname(path)
    addresses, servers = {}, []
    # The bake first (servers depend on it), then the servers, then the batch.
    order = sorted(services, key=lambda s: (0 if s == "bake" else 2 if s == "batch" else 1, s))
    for name in order:
        svc = services[name]
        where = f"compose {name}"
        check(svc.get("image") == IMAGE, f"{where}: image {svc.get('image')}, want {IMAGE}")
        build = svc.get("build", {})
        check(os.path.normpath(os.path.join(base, build.get("context", "."),
                                            build.get("dockerfile", "Dockerfile"))) ==
              os.path.join(repo, "deploy/Dockerfile"), f"{where}: does not build deploy/Dockerfile")
        entry = svc.get("entrypoint", docker["entrypoint"])
        args = svc.get("command", docker["cmd"] if "entrypoint" not in svc else [])
        entry = entry if isinstance(entry, list) else shlex.split(entry)
        args = args if isinstance(args, list) else shlex.split(args)
        binary = runner.binary(entry[0], where)
        full = entry[1:] + [str(a) for a in args]
        runner.validate(binary, full, where)
        mounts = {}
        for v in svc.get("volumes", []):
            src, dst = v.split(":")[:2]
            if src.startswith("."):
                host = os.path.normpath(os.path.join(base, src))
                mounts[dst] = host if dst == "/jobs" else tempfile.mkdtemp(dir=runner.tmp)
            else:
                mounts[dst] = tempfile.mkdtemp(dir=runner.tmp)
        if binary in ("aperture-server", "aperture-tex"):
            check(any(v.split(":")[:2] == ["shm", "/dev/shm"] for v in svc.get("volumes", [])),
                  f"{where}: the shm volume is not mounted at /dev/shm")
            check((flag_value(full, "store") or "").startswith("/dev/shm/"),
                  f"{where}: --store is not under /dev/shm")
        if binary == "aperture-server":
            port = listen_port(full, where)
            published = [str(p).rsplit(":", 1)[-1] for p in svc.get("ports", [])]
            check(published and all(int(p) == port for p in published),
                  f"{where}: published container ports {published} are not --listen's {port}")
            check(port in docker["expose"], f"{where}: --listen port {port} is not the image's "
                  f"EXPOSE {docker['expose']}")
            hc = docker["healthcheck"]
            check(flag_value(hc, "server") == f"127.0.0.1:{port}", f"{where}: the image's "
                  f"HEALTHCHECK asks {flag_value(hc, 'server')}, the server listens on {port}")
            check_grace(where, full, seconds(svc.get("stop_grace_period", "10s")))
            p, address, _ = runner.start_server(full, mounts, where)
            if address:
                # The image's HEALTHCHECK command against it.
                runner.run_tool("aperture", set_flag(hc[1:], "server", address), {},
                                f"{where} HEALTHCHECK", want_text="SERVING")
                addresses.setdefault(f"{name}:{port}", []).append(address)
                servers.append((p, where, full))
        elif binary == "aperture" and name == "batch":
            out = mounts.get("/frames")
            mapped = set_flag(full, "servers",
                              map_servers(flag_value(full, "servers"), addresses, where))
            runner.run_tool("aperture", mapped, mounts, where, want_text="0 failed")
            runner.run_tool("aperture", ["batch", map_paths([full[1]], mounts)[0], "--check",
                                         "-o", out], {}, f"{where} (check)",
                            want_text="0 missing, 0 invalid")
        else:
            runner.run_tool(binary, full, mounts, where)
    for p, where, full in servers:
        runner.procs.stop(p, where, float(flag_value(full, "grace_s") or 10))
    note(f"compose: {len(services)} services run as processes (bake, 2 servers with the image's "
         "HEALTHCHECK, the batch over both)")


def load_k8s(repo):
    docs = {}
    k8s = os.path.join(repo, "deploy/k8s")
    for fname in sorted(os.listdir(k8s)):
        if not fname.endswith(".yaml"):
            continue
        with open(os.path.join(k8s, fname)) as f:
            for doc in yaml.safe_load_all(f):
                if doc is None:
                    continue
                if fname == "kustomization.yaml":
                    docs[("Kustomization", "kustomization")] = (fname, doc)
                    continue
                check("apiVersion" in doc and "kind" in doc and "name" in doc.get("metadata", {}),
                      f"{fname}: a document without apiVersion, kind or metadata.name")
                docs[(doc["kind"], doc["metadata"]["name"])] = (fname, doc)
    return docs


def pod_mounts(pod, where, runner, configmaps):
    """Host directories for the pod's volumes (ConfigMap data written out)."""
    dirs = {}
    for v in pod.get("volumes", []):
        d = tempfile.mkdtemp(dir=runner.tmp)
        if "configMap" in v:
            name = v["configMap"]["name"]
            if check(name in configmaps, f"{where}: ConfigMap {name} is defined nowhere"):
                for key, text in configmaps[name]["data"].items():
                    with open(os.path.join(d, key), "w") as f:
                        f.write(text)
        dirs[v["name"]] = d
    return dirs


def container_mounts(container, volumes, where):
    mounts = {}
    for m in container.get("volumeMounts", []):
        check(m["name"] in volumes, f"{where}: volumeMount {m['name']} names no volume")
        mounts[m["mountPath"]] = volumes.get(m["name"], "/nonexistent")
    return mounts


def expand_env(args, container, where):
    names = {e["name"] for e in container.get("env", [])}
    out = []
    for a in args:
        for var in re.findall(r"\$\((\w+)\)", a):
            check(var in names, f"{where}: $({var}) in args, but no env {var}")
        out.append(a)
    return out


def check_k8s(repo, runner, docker):
    docs = load_k8s(repo)
    kinds = {k for k, _ in docs}
    for kind in ("Deployment", "Service", "HorizontalPodAutoscaler", "Job", "ConfigMap",
                 "PersistentVolumeClaim"):
        check(kind in kinds, f"deploy/k8s has no {kind}")
    configmaps = {n: d for (k, n), (_, d) in docs.items() if k == "ConfigMap"}
    pvcs = {n for (k, n) in docs if k == "PersistentVolumeClaim"}
    deployments = {n: d for (k, n), (_, d) in docs.items() if k == "Deployment"}
    services = {n: d for (k, n), (_, d) in docs.items() if k == "Service"}

    kust = docs.get(("Kustomization", "kustomization"))
    if check(kust, "deploy/k8s has no kustomization.yaml"):
        listed = set(kust[1].get("resources", []))
        for fname in {f for f, _ in docs.values()} - {"kustomization.yaml"}:
            if fname.startswith(("batch", "check")):
                continue
            check(fname in listed, f"kustomization.yaml does not list {fname}")
        for img in kust[1].get("images", []):
            check(img["name"] == IMAGE.split(":")[0], f"kustomization: image {img['name']}")

    addresses, servers = {}, []
    bake_store = None
    for name, dep in deployments.items():
        where = f"Deployment {name}"
        pod = dep["spec"]["template"]["spec"]
        labels = dep["spec"]["template"]["metadata"]["labels"]
        check(dep["spec"]["selector"]["matchLabels"].items() <= labels.items(),
              f"{where}: selector does not match the pod labels")
        sc = pod.get("securityContext", {})
        check(sc.get("runAsNonRoot") is True, f"{where}: not runAsNonRoot")
        shm = [v for v in pod.get("volumes", []) if v.get("emptyDir", {}).get("medium") == "Memory"]
        check(shm, f"{where}: no emptyDir of medium Memory for the store")
        volumes = pod_mounts(pod, where, runner, configmaps)
        inits = pod.get("initContainers", [])
        check(any(c.get("command", [""])[0] == "aperture-tex" and c.get("args", [""])[0] == "bake"
                  for c in inits), f"{where}: no init container running aperture-tex bake")
        for c in inits + pod["containers"]:
            cw = f"{where} container {c['name']}"
            check(c.get("image") == IMAGE, f"{cw}: image {c.get('image')}, want {IMAGE}")
            check("requests" in c.get("resources", {}), f"{cw}: no resource requests")
            check(any(m["mountPath"] == "/dev/shm" and m["name"] in {v["name"] for v in shm}
                      for m in c.get("volumeMounts", [])),
                  f"{cw}: the Memory emptyDir is not mounted at /dev/shm")
            entry = c.get("command", docker["entrypoint"])
            args = [str(a) for a in c.get("args", docker["cmd"] if "command" not in c else [])]
            binary = runner.binary(entry[0], cw)
            full = expand_env(entry[1:] + args, c, cw)
            runner.validate(binary, full, cw)
            mounts = container_mounts(c, volumes, cw)
            check((flag_value(full, "store") or "").startswith("/dev/shm/"),
                  f"{cw}: --store is not under /dev/shm")
            if c in inits:
                bake_store = flag_value(full, "store")
                runner.run_tool(binary, full, mounts, cw)
                continue
            check(binary == "aperture-server", f"{cw}: runs {binary}, not aperture-server")
            check(flag_value(full, "store") == bake_store, f"{cw}: --store is not the baked one")
            port = listen_port(full, cw)
            ports = {p.get("name"): p["containerPort"] for p in c.get("ports", [])}
            check(list(ports.values()) == [port], f"{cw}: containerPorts {ports} are not --listen's"
                  f" {port}")
            for probe in ("startupProbe", "readinessProbe", "livenessProbe"):
                spec = c.get(probe, {})
                if check("grpc" in spec, f"{cw}: {probe} is not a native gRPC probe"):
                    p = spec["grpc"]["port"]
                    check(ports.get(p, p) == port,
                          f"{cw}: {probe} port {p} is not --listen's {port}")
            cpu = str(c["resources"]["requests"].get("cpu", ""))
            check(cpu.isdigit() and int(flag_value(full, "threads") or 0) == int(cpu),
                  f"{cw}: --threads {flag_value(full, 'threads')} is not the CPU request {cpu}")
            pre = c.get("lifecycle", {}).get("preStop", {}).get("exec", {}).get("command", [])
            pre_s = float(pre[1]) if len(pre) == 2 and pre[0] == "sleep" else 0
            check_grace(cw, full, pod.get("terminationGracePeriodSeconds", 30), pre_s)
            # Services selecting these pods: their target port is the server's.
            for sname, svc in services.items():
                if not svc["spec"]["selector"].items() <= labels.items():
                    continue
                check(svc["spec"].get("clusterIP") == "None", f"Service {sname} is not headless")
                for sp in svc["spec"]["ports"]:
                    target = sp.get("targetPort", sp["port"])
                    check(ports.get(target, target) == port,
                          f"Service {sname}: targetPort {target} is not the server's {port}")
                    p, address, _ = runner.start_server(full, mounts, cw)
                    if address:
                        addresses.setdefault(f"{sname}:{sp['port']}", []).append(address)
                        servers.append((p, cw, full))
                        # What the probes ask: grpc.health.v1 Check.
                        runner.run_tool("aperture", ["health", "--server", address], {},
                                        f"{cw} probe", want_text="SERVING")
    check(addresses, "no Service selects the server pods")

    for (kind, name), (fname, doc) in docs.items():
        if kind == "HorizontalPodAutoscaler":
            ref = doc["spec"]["scaleTargetRef"]
            check(ref["kind"] == "Deployment" and ref["name"] in deployments,
                  f"HPA {name}: scales {ref}, no such Deployment")
            check(doc["spec"]["minReplicas"] <= doc["spec"]["maxReplicas"],
                  f"HPA {name}: min > max")

    # Jobs: the Indexed batch first (every shard, over the local servers), then the check.
    jobs = sorted(((n, d) for (k, n), (_, d) in docs.items() if k == "Job"),
                  key=lambda nd: nd[1]["spec"].get("completionMode") != "Indexed")
    small_job = os.path.join(repo, "deploy/jobs/demo-24.json")
    for name, job in jobs:
        where = f"Job {name}"
        pod = job["spec"]["template"]["spec"]
        volumes = pod_mounts(pod, where, runner, configmaps)
        for v in pod.get("volumes", []):
            if "persistentVolumeClaim" in v:
                check(v["persistentVolumeClaim"]["claimName"] in pvcs,
                      f"{where}: PVC {v['persistentVolumeClaim']['claimName']} is defined nowhere")
                volumes[v["name"]] = os.path.join(runner.tmp, "frames")  # one shared volume
                os.makedirs(volumes[v["name"]], exist_ok=True)
        (c,) = pod["containers"]
        cw = f"{where} container {c['name']}"
        check(c.get("image") == IMAGE, f"{cw}: image {c.get('image')}, want {IMAGE}")
        entry = c.get("command", docker["entrypoint"])
        args = [str(a) for a in c.get("args", [])]
        binary = runner.binary(entry[0], cw)
        full = expand_env(entry[1:] + args, c, cw)
        runner.validate(binary, full, cw)
        mounts = container_mounts(c, volumes, cw)
        job_file = map_paths([full[1]], mounts)[0]
        check(os.path.isfile(job_file), f"{cw}: the job file {full[1]} is in no mounted volume")
        # The ConfigMap's job file parses (a --check of an empty directory: all missing).
        runner.run_tool("aperture", ["batch", job_file, "--check", "-o",
                                     tempfile.mkdtemp(dir=runner.tmp)], {}, f"{cw} job file",
                        want_rc=1, want_text=" missing, 0 invalid")
        # Then the container's own args on the small 24-frame job, so it runs in seconds.
        small = [small_job if a == full[1] else a for a in full]
        if job["spec"].get("completionMode") == "Indexed":
            n = job["spec"]["completions"]
            shard = flag_value(full, "shard") or ""
            check(shard == f"$(SHARD)/{n}", f"{cw}: --shard {shard}, want $(SHARD)/{n} "
                  "(completions)")
            env = {e["name"]: e for e in c.get("env", [])}
            check(env.get("SHARD", {}).get("valueFrom", {}).get("fieldRef", {}).get("fieldPath")
                  == "metadata.annotations['batch.kubernetes.io/job-completion-index']",
                  f"{cw}: SHARD is not the pod's completion index")
            check(job["spec"].get("parallelism", 1) <= n, f"{where}: parallelism > completions")
            small = set_flag(small, "servers",
                             map_servers(flag_value(full, "servers"), addresses, cw))
            for i in range(n):
                runner.run_tool("aperture", [a.replace("$(SHARD)", str(i)) for a in small],
                                mounts, f"{cw} index {i}", want_text="0 failed")
        else:
            runner.run_tool("aperture", small, mounts, cw, want_text="24 valid, 0 missing")
    for p, where, full in servers:
        runner.procs.stop(p, where, float(flag_value(full, "grace_s") or 10))
    note(f"k8s: {len(docs)} documents; the Deployment's bake and server, its probes, the Indexed "
         "Job's shards over the Service's servers and the check job run as processes")


def main():
    ap = argparse.ArgumentParser()
    for a in ("repo", "server", "client", "tex", "render"):
        ap.add_argument("--" + a, required=True)
    opts = ap.parse_args()
    repo = os.path.abspath(opts.repo)
    bins = {"aperture-server": opts.server, "aperture": opts.client, "aperture-tex": opts.tex,
            "aperture-render": opts.render}
    bins = {k: os.path.abspath(v) for k, v in bins.items()}
    start = time.time()
    absl = {b: AbslFlags(bins[b]) for b in ABSL_BINARIES}
    tex = TexCommands(bins["aperture-tex"])
    procs = Processes()
    tmp = tempfile.mkdtemp(prefix="aperture-manifests-")
    try:
        docker = check_dockerfile(repo, bins)
        if "entrypoint" in docker:
            where = "Dockerfile CMD"
            runner = Runner(bins, absl, tex, procs, tmp, os.path.join(tmp, "store"))
            check(docker["entrypoint"] == ["aperture-server"], "ENTRYPOINT is not aperture-server")
            runner.validate("aperture-server", docker["cmd"], where)
            port = listen_port(docker["cmd"], where)
            check(docker["expose"] == [port], f"EXPOSE {docker['expose']} is not --listen's {port}")
            hc = docker["healthcheck"]
            runner.validate(runner.binary(hc[0], "HEALTHCHECK"), hc[1:], "HEALTHCHECK")
            check(flag_value(hc, "server") == f"127.0.0.1:{port}", "HEALTHCHECK asks "
                  f"{flag_value(hc, 'server')}, the server listens on {port}")
            p, address, _ = runner.start_server(docker["cmd"], {}, where)
            if address:
                runner.run_tool("aperture", set_flag(hc[1:], "server", address), {},
                                "HEALTHCHECK", want_text="SERVING")
                procs.stop(p, where, float(flag_value(docker["cmd"], "grace_s") or 10))
            check_compose(repo, runner, docker)
            check_k8s(repo, runner, docker)
    finally:
        procs.cleanup()
        shutil.rmtree(tmp, ignore_errors=True)
    if errors:
        for e in errors:
            print("FAIL:", e)
        sys.exit(1)
    print(f"PASS ({time.time() - start:.1f} s)")


if __name__ == "__main__":
    main()
