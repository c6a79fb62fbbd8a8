#!/usr/bin/env python3
"""mutate.py: mutation testing of archquake (`make mutate`).

Each mutant of tests/mutants.txt is a small deliberate bug, given as the
file, the exact source text it replaces (which must occur exactly once) and
the replacement.  One at a time, the mutated file is compiled (from standard
input, so the work tree is never changed) and linked with the other objects
of build/mut (the tests without sanitizers, -O1), and the test runner runs
until its first failed test: first the mutated stage's tests, then all.  A
mutated header (.h) is written into a copy of src/ under build/mut/m, and
every source and test file that includes it, directly or not, is compiled
again against that copy.  A mutant is "killed" when the tests fail (or
time out, or the mutant does not compile), "SURVIVED" when they pass, and
"stale" when its source text is no longer found once: a stale mutant fails
the run, so the list follows the code.  A survivor fails the run too unless
its block says "equivalent: REASON" (listed in docs/testing.md).

Usage: python3 tests/mutate.py [SUBSTRING]   (only mutants whose id contains it)
Environment (set by the Makefile): CC, AQ_CFLAGS, AQ_LIBS, LDFLAGS;
MUTATE_TIMEOUT (s per run of the tests, default 120; a hang counts as killed).
Prints one line per mutant, then "N mutants, K survived"; exit status 1 if
a mutant not marked equivalent survived, or one is stale.
"""
import os
import shlex
import signal
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MUT = os.path.join("build", "mut")
LIST = os.path.join("tests", "mutants.txt")
# Test-name prefixes run first for a mutant in each stage.
STAGE_TESTS = [("src/arch/stepper.c", "dyn_"), ("src/arch/eom.c", "dyn_"),
               ("src/app/suite_record.c", "select_cli_suite"),
               ("src/job/subject.c", "select_cli_suite"),
               ("src/io/", "io_"), ("src/signal/", "signal_"), ("src/arch/", "arch_"),
               ("src/report/", "report_"), ("src/app/", "app_"),
               ("src/util/diskcache.c", "cache_"), ("src/job/subject_cache.c", "cache_"),
               ("src/select/", "select_")]


def parse_list(path):
    """Blocks separated by lines of '===':
         id: short-name
         file: src/...
         --- (the exact text)
         +++ (the replacement)
       Text after '---' up to '+++' is the source, after '+++' up to the
       block's end the replacement (a trailing newline is dropped)."""
    muts = []
    with open(path, encoding="utf-8") as f:
        blocks = f.read().split("\n===\n")
    for b in blocks:
        lines = b.split("\n")
        meta, old, new, mode = {}, [], [], None
        for ln in lines:
            if mode is None and ln.startswith("#"):
                continue
            if ln == "---":
                mode = "old"
            elif ln == "+++":
                mode = "new"
            elif mode == "old":
                old.append(ln)
            elif mode == "new":
                new.append(ln)
            elif ":" in ln:
                k, v = ln.split(":", 1)
                meta[k.strip()] = v.strip()
        if not meta:
            continue
        while new and new[-1] == "":
            new.pop()
        muts.append((meta["id"], meta["file"], "\n".join(old), "\n".join(new),
                     meta.get("equivalent", "")))
    return muts


def run_tests(cmd, env, timeout):
    """Run the runner in its own process group; on timeout end the whole
    group (a mutant may make a CLI the tests start loop for ever)."""
    p = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         start_new_session=True)
    try:
        out, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        raise
    return subprocess.CompletedProcess(cmd, p.returncode, out, err)


def includers(cc, cflags, header, sources):
    """The sources that include header, directly or through other headers
    (by the compiler's own dependency list)."""
    out = []
    for c in sources:
        dp = subprocess.run([cc] + [f for f in cflags if f.startswith(("-I", "-D", "-std"))] +
                            ["-MM", c], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
        deps = dp.stdout.decode().replace("\\\n", " ").split()
        if any(os.path.normpath(d) == os.path.normpath(header) for d in deps):
            out.append(c)
    return out


def compile_with_header(cc, cflags, header, text, sources):
    """The mutated header in a copy of src/; every includer compiled against
    it.  Returns {source: object}, or None if one does not compile."""
    tree = os.path.join(MUT, "m", "tree")
    subprocess.run(["rm", "-rf", tree], check=True)
    os.makedirs(tree)
    subprocess.run(["cp", "-r", "src", os.path.join(tree, "src")], check=True)
    with open(os.path.join(tree, header), "w", encoding="utf-8") as f:
        f.write(text)
    flags = [("-I" + os.path.join(tree, "src")) if f == "-Isrc" else f for f in cflags]
    objs = {}
    for c in includers(cc, cflags, header, sources):
        # a source of src/ is compiled from the copy, so that its own
        # directory (searched first by #include "...") holds the mutant
        src = os.path.join(tree, c) if c.startswith("src/") else c
        o = os.path.join(MUT, "m", c.replace("/", "_")[:-2] + ".o")
        cp = subprocess.run([cc] + flags + ["-O1", "-g", "-c", "-o", o, src],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        if cp.returncode != 0:
            return None
        objs[c] = o
    return objs


def main():
    os.chdir(ROOT)
    cc = os.environ.get("CC", "cc")
    cflags = shlex.split(os.environ.get("AQ_CFLAGS", "-std=c11 -Isrc"))
    libs = shlex.split(os.environ.get("AQ_LIBS", "-lm"))
    ldflags = shlex.split(os.environ.get("LDFLAGS", ""))
    timeout = float(os.environ.get("MUTATE_TIMEOUT", "120"))
    only = sys.argv[1] if len(sys.argv) > 1 else ""
    muts = [m for m in parse_list(LIST) if only in m[0]]
    lib_src = sorted(
        os.path.join(d, f)
        for d in ["src"] + [os.path.join("src", x) for x in os.listdir("src")]
        if os.path.isdir(d)
        for f in os.listdir(d) if f.endswith(".c"))
    # as the Makefile's LIB_SRC: the MPI driver is built only by `make mpi`
    lib_src = [c for c in lib_src if c != os.path.join("src", "app", "mpi.c")]
    test_src = sorted(os.path.join("tests", f) for f in os.listdir("tests")
                      if f.startswith("test_") and f.endswith(".c") or f == "runner.c")
    obj = lambda c: os.path.join(MUT, c[:-2] + ".o")
    for c in lib_src + test_src:
        if not os.path.exists(obj(c)):
            sys.exit("mutate: %s missing: run make build/mut/runner first" % obj(c))
    os.makedirs(os.path.join(MUT, "m"), exist_ok=True)
    runner, aqbin = os.path.join(MUT, "m", "runner"), os.path.join(MUT, "m", "archquake")
    mobj = os.path.join(MUT, "m", "mutant.o")
    # the cache of prepared records (docs/cache.md) under build/mut, emptied
    # for every mutant (each build's entries are its own anyway)
    cache = os.path.abspath(os.path.join(MUT, "cache"))
    env = dict(os.environ, AQ_BIN=aqbin, AQ_TEST_STOP_FIRST="1", XDG_CACHE_HOME=cache)
    env.pop("AQ_TEST_VERBOSE", None)
    survived, unexplained, stale, t_start = [], [], [], time.time()
    # a mutant's link must fail only because of the mutant: the unmutated
    # objects must link with these flags (else run through `make mutate`)
    for out, o in ((runner, [obj(c) for c in test_src + lib_src if c != "src/main.c"]),
                   (aqbin, [obj(c) for c in lib_src])):
        lp = subprocess.run([cc] + ldflags + ["-o", out] + o + libs,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        if lp.returncode != 0:
            sys.stderr.write(lp.stderr.decode(errors="replace")[-2000:])
            sys.exit("mutate: the unmutated objects do not link with AQ_LIBS=%r: "
                     "run it as `make mutate`" % " ".join(libs))
    # the unmutated build must pass, or every mutant would look killed
    base = subprocess.run([os.path.join(MUT, "runner")],
                          env=dict(env, AQ_BIN=os.path.join(MUT, "archquake")),
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    if base.returncode != 0:
        sys.stderr.write(base.stderr.decode(errors="replace")[-3000:])
        sys.exit("mutate: the tests fail without any mutant (build/mut): fix them first")
    print("unmutated: %s (%.0f s)" % (base.stdout.decode().strip().splitlines()[-1],
                                      time.time() - t_start), flush=True)
    for mid, path, old, new, equiv in muts:
        t0 = time.time()
        subprocess.run(["rm", "-rf", cache], check=True)
        try:
            with open(path, encoding="utf-8") as f:
                src = f.read()
        except OSError:
            src = ""
        n = src.count(old) if old else 0
        if n != 1:
            stale.append(mid)
            print("%-28s %-26s stale (%s)" % (mid, path,
                  "text not found" if n == 0 else "text found %d times" % n), flush=True)
            continue
        msrc = src.replace(old, new, 1)
        if path.endswith(".h"):
            mobjs = compile_with_header(cc, cflags, path, msrc, lib_src + test_src)
        else:
            d = os.path.dirname(path)
            cp = subprocess.run([cc] + cflags + ["-O1", "-g", "-iquote", d, "-x", "c", "-c",
                                 "-o", mobj, "-"], input=msrc.encode(),
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE)
            mobjs = {path: mobj} if cp.returncode == 0 else None
        if mobjs is None:
            print("%-28s %-26s killed (does not compile)" % (mid, path), flush=True)
            continue
        if not mobjs:
            stale.append(mid)
            print("%-28s %-26s stale (no source includes it)" % (mid, path), flush=True)
            continue
        objs = [mobjs.get(c, obj(c)) for c in lib_src if c != "src/main.c"]
        tobjs = [mobjs.get(c, obj(c)) for c in test_src]
        mainobj = mobjs.get("src/main.c", obj("src/main.c"))
        link_ok = all(subprocess.run([cc] + ldflags + ["-o", out] + o + libs).returncode == 0
                      for out, o in ((runner, tobjs + objs), (aqbin, [mainobj] + objs)))
        if not link_ok:
            print("%-28s %-26s killed (does not link)" % (mid, path), flush=True)
            continue
        try:
            # the mutated stage's own tests first (most mutants die there),
            # then all of them
            first = next((f for pre, f in STAGE_TESTS if path.startswith(pre)), None)
            rp = None
            if first:
                rp = run_tests([runner, first], env, timeout)
            if rp is None or rp.returncode == 0:
                rp = run_tests([runner], env, timeout)
            if rp.returncode == 0:
                verdict = "SURVIVED" + (" (equivalent: %s)" % equiv if equiv else "")
                survived.append(mid)
                if not equiv:
                    unexplained.append(mid)
            else:
                fails = [ln.split()[1] for ln in rp.stderr.decode(errors="replace").splitlines()
                         if ln.startswith("FAIL ") and "checks failed" in ln]
                verdict = "killed by %s" % (fails[0] if fails else
                                            "exit status %d" % rp.returncode)
        except subprocess.TimeoutExpired:
            verdict = "killed (tests timed out after %g s)" % timeout
        print("%-28s %-26s %s (%.1f s)" % (mid, path, verdict, time.time() - t0), flush=True)
    ran = len(muts) - len(stale)
    print("time %.0f s; stale: %d%s" % (time.time() - t_start, len(stale),
          " (" + ", ".join(stale) + ")" if stale else ""))
    if survived:
        print("survived: " + ", ".join(survived))
    print("%d mutants, %d survived" % (ran, len(survived)))
    return 1 if unexplained or stale else 0


if __name__ == "__main__":
    sys.exit(main())
