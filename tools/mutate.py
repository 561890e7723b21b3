#!/usr/bin/env python3
"""mutate.py — mutation check of the wrinkle headers (`make mutate`; issue 20).

Applies each mutant of a list (default tests/mutants.txt) to a scratch copy of the tree, one at a
time, rebuilds what the mutant changes, runs the unit tests it names (Criterion --filter, stopping at
the first failure) and then the fast validations it names, and reports each mutant as
  KILLED     a unit test failed or crashed, a named validation lost a passing row, or a run timed out;
  SURVIVED   everything it was checked against still passes (each survivor needs an entry in
             tests/MUTANTS.md: an equivalent mutant, or the test that now kills it);
  STALE      its anchor text is not in the header (the code moved: re-anchor the mutant);
  AMBIGUOUS  its anchor occurs more than once (lengthen the anchor);
  NOBUILD    the mutated tree does not compile (not a useful mutant: change it).
The working files are never touched: the tree is copied (git ls-files plus untracked files that are
not ignored) to a scratch directory, by default $TMPDIR/wrinkle-mutate-<uid>.

Speed. Everything that does not change is built once: the Criterion test objects, the driver-helper
objects and the validators' objects. For module M (header include/wrinkle/M.h), a "rest" unit holds
every implementation except M's (built once per M, cached by the headers' content) and the mutant
rebuilds only M's implementation unit (M plus core.h, linked with --allow-multiple-definition so the
core copies, identical, do not clash). A mutant in a header's declaration part (a macro, an inline)
can reach other units, so it rebuilds everything, and so does a mutant in a driver-side helper
(drivers/lib/*.c, e.g. the CLI parsing every driver and validator shares: tests/test_cli.c kills
it). Each step has a timeout (3x the pristine run + 30 s
for tests).

Mutant list format (one block per mutant; '#' starts a comment line):
    == <id> | <header path> | <criterion filter or *> | <validations, comma-separated, or ->
    - <anchor line 1>              (exact text, leading/trailing spaces of each line ignored only
    - <anchor line 2 ...>           for matching the line's indentation: see below)
    + <replacement line 1 ...>
The anchor is the '-' lines joined by newlines, each stripped of its leading whitespace and matched
against the header's lines with their indentation; it must occur exactly once. The replacement keeps
the first anchor line's indentation. No '+' lines deletes the anchor. The filter may be an extglob
(`@(statics|loads)/*`). Validations are bin/validate_<name> drivers; a validation kills a mutant when
a quantity that passes on the pristine tree fails (or disappears), or the driver exits abnormally.

Usage: tools/mutate.py [--list FILE] [--only ID[,ID...]] [--scratch DIR] [--keep-going] [-j N]
Exit status: 0 when no mutant survives and none is stale, 1 otherwise, 2 on a setup error.
"""
import argparse
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import time

SAN = ["-fsanitize=address,undefined,float-cast-overflow", "-fno-omit-frame-pointer", "-fno-sanitize-recover=all"]


def make_variable(name, default):
    """The Makefile's value of `name` (so the mutation builds never drift from `make test`'s flags);
    `default` when make cannot tell (run outside the tree)."""
    try:
        out = subprocess.run(["make", "-s", "--no-print-directory", "-f", "Makefile", "-f", "-", "_wr_print_var"],
                             input="_wr_print_var:\n\t@echo $(%s)\n" % name, capture_output=True, text=True,
                             timeout=30)
        if out.returncode == 0 and out.stdout.strip():
            return out.stdout.split()
    except (OSError, subprocess.SubprocessError):
        pass
    return default


# The Makefile's common flags without its optimisation level (set per flavour below) and its libraries.
COMMON = [f for f in make_variable("CFLAGS_COMMON", ["-g", "-Wall", "-Wextra", "-pedantic", "-ffp-contract=off",
                                                     "-Iinclude", "-Idrivers/lib", "-I/usr/include/suitesparse",
                                                     "-DWR_USE_CHOLMOD=1", "-DWR_USE_FFTW=1", "-DWR_USE_LIBPNG=1"])
          if not re.fullmatch(r"-O.*", f)]
# the test binary also gets ARPACK (eigen.h, statics.h ON STABILITY), as the Makefile builds it
ARPACK_FLAGS = make_variable("ARPACK_FLAGS", ["-DWR_USE_ARPACK=1"])
TEST_FLAGS = ["-std=c11"] + COMMON + ARPACK_FLAGS + ["-O1"] + SAN          # as the Makefile's test binary
VALID_FLAGS = ["-std=c11"] + COMMON + ["-O2"]                # as the Makefile's drivers/validators
LIBS = make_variable("LIBS", ["-lcjson", "-lcholmod", "-lfftw3", "-lpng", "-lgsl", "-lgslcblas", "-lm"]) + \
    make_variable("ARPACK_LIBS", ["-larpack"])
MODULE_GUARD = re.compile(r"^#ifndef WRINKLE_([A-Z0-9_]+)_IMPLEMENTATION_DONE", re.M)


def log(*a):
    print(*a, flush=True)


class Mutant:
    def __init__(self, mid, header, filt, valids, anchor, repl, lineno):
        self.id, self.header, self.filter, self.valids = mid, header, filt, valids
        self.anchor, self.repl, self.lineno = anchor, repl, lineno
        self.status, self.detail, self.seconds = None, "", 0.0


def parse_list(path):
    muts, cur = [], None
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            s = line.rstrip("\n")
            if s.startswith("=="):
                parts = [p.strip() for p in s[2:].split(" | ")]
                if len(parts) != 4:
                    raise SystemExit("%s:%d: expected '== id | header | filter | validations'" % (path, n))
                valids = [] if parts[3] in ("", "-") else [v.strip() for v in parts[3].split(",")]
                cur = Mutant(parts[0], parts[1], parts[2], valids, [], [], n)
                if any(m.id == cur.id for m in muts):
                    raise SystemExit("%s:%d: duplicate mutant id %s" % (path, n, cur.id))
                muts.append(cur)
            elif s.startswith("- ") or s == "-":
                if cur is None:
                    raise SystemExit("%s:%d: anchor line before any '==' header" % (path, n))
                cur.anchor.append(s[2:].strip())
            elif s.startswith("+ ") or s == "+":
                if cur is None:
                    raise SystemExit("%s:%d: replacement line before any '==' header" % (path, n))
                cur.repl.append(s[2:])
            elif s.strip() == "" or s.lstrip().startswith("#"):
                continue
            else:
                raise SystemExit("%s:%d: cannot parse: %s" % (path, n, s))
    for m in muts:
        if not m.anchor:
            raise SystemExit("%s:%d: mutant %s has no anchor" % (path, m.lineno, m.id))
    return muts


def find_anchor(text, anchor):
    """Line-based match ignoring each line's leading whitespace. Returns list of (start, end) char
    offsets of every occurrence (start at the first line's first non-blank character)."""
    lines = text.split("\n")
    offs, o = [], 0
    for ln in lines:
        offs.append(o)
        o += len(ln) + 1
    hits = []
    k = len(anchor)
    if k == 1:
        a = anchor[0]
        for i, ln in enumerate(lines):
            j = ln.find(a)
            while j >= 0:
                hits.append((offs[i] + j, offs[i] + j + len(a)))
                j = ln.find(a, j + 1)
        return hits
    for i in range(len(lines) - k + 1):
        first = lines[i]
        j = first.find(anchor[0])
        if j < 0 or first[j:].rstrip() != anchor[0]:
            continue
        ok = all(lines[i + t].strip() == anchor[t] for t in range(1, k - 1))
        last = lines[i + k - 1].lstrip()
        if ok and last.startswith(anchor[-1]):
            end = offs[i + k - 1] + (len(lines[i + k - 1]) - len(last)) + len(anchor[-1])
            hits.append((offs[i] + j, end))
    return hits


def apply_mutant(text, m, start, end):
    line_start = text.rfind("\n", 0, start) + 1
    indent = re.match(r"[ \t]*", text[line_start:start]).group(0) if text[line_start:start].strip() == "" else ""
    repl = ("\n" + indent).join(r.strip() if i else r.strip() for i, r in enumerate(m.repl)) if m.repl else ""
    return text[:start] + repl + text[end:]


class Tree:
    def __init__(self, src, scratch, jobs):
        self.src, self.dir, self.jobs = src, scratch, jobs
        self.obj = os.path.join(scratch, "build", "mutate")
        self.pristine = {}

    def run(self, cmd, timeout=None, env=None, capture=True):
        return subprocess.run(cmd, cwd=self.dir, timeout=timeout, env=env,
                              stdout=subprocess.PIPE if capture else None,
                              stderr=subprocess.STDOUT if capture else None, text=True)

    def copy(self):
        files = subprocess.run(["git", "ls-files", "-co", "--exclude-standard"], cwd=self.src,
                               stdout=subprocess.PIPE, text=True, check=True).stdout.split("\n")
        keep = ("include/", "tests/", "drivers/", "validation/", "examples/")
        os.makedirs(self.dir, exist_ok=True)
        for f in files:
            if not f or not f.startswith(keep) or not os.path.isfile(os.path.join(self.src, f)):
                continue
            if f.startswith("validation/results/") or f.startswith("validation/figures/"):
                continue
            d = os.path.join(self.dir, f)
            os.makedirs(os.path.dirname(d), exist_ok=True)
            shutil.copy2(os.path.join(self.src, f), d)
        os.makedirs(self.obj, exist_ok=True)
        os.makedirs(os.path.join(scratch_build := os.path.join(self.dir, "build"), "test"), exist_ok=True)
        # the headers, and the driver-side helpers (drivers/lib/*.c: a mutant there rebuilds everything)
        for d, ext in ((os.path.join("include", "wrinkle"), ".h"), (os.path.join("drivers", "lib"), ".c")):
            for h in os.listdir(os.path.join(self.dir, d)):
                p = os.path.join(d, h)
                if not h.endswith(ext) or h == "impl.c":
                    continue
                with open(os.path.join(self.dir, p), encoding="utf-8") as f:
                    self.pristine[p] = f.read()

    def restore(self, header):
        with open(os.path.join(self.dir, header), "w", encoding="utf-8") as f:
            f.write(self.pristine[header])

    def write(self, header, text):
        with open(os.path.join(self.dir, header), "w", encoding="utf-8") as f:
            f.write(text)

    def headers_hash(self):
        h = hashlib.sha1()
        for k in sorted(self.pristine):
            h.update(k.encode() + b"\0" + self.pristine[k].encode())
        return h.hexdigest()[:12]

    def compile_many(self, jobs_list):
        """jobs_list: list of (flags, src, obj). Runs up to self.jobs at once; returns error text or None."""
        procs, err = [], None
        pending = list(jobs_list)
        while pending or procs:
            while pending and len(procs) < self.jobs:
                flags, src, obj = pending.pop(0)
                cmd = ["nice", "cc"] + flags + ["-c", src, "-o", obj]
                procs.append((subprocess.Popen(cmd, cwd=self.dir, stdout=subprocess.PIPE,
                                               stderr=subprocess.STDOUT, text=True), src))
            p, src = procs.pop(0)
            out, _ = p.communicate()
            if p.returncode != 0 and err is None:
                err = "%s: %s" % (src, out.strip().split("\n")[0] if out.strip() else "failed")
        return err

    # -- module units ---------------------------------------------------------------------------
    def modules(self):
        mods = {}
        for p, t in self.pristine.items():
            m = MODULE_GUARD.search(t)
            if m:
                mods[p] = m.group(1)
        return mods

    def unit_source(self, name, skip):
        """An implementation unit defining WRINKLE_IMPLEMENTATION with the DONE guards of `skip` set."""
        path = os.path.join(self.obj, name + ".c")
        with open(path, "w") as f:
            f.write("/* generated by tools/mutate.py */\n#define WRINKLE_IMPLEMENTATION\n")
            for g in sorted(skip):
                f.write("#define WRINKLE_%s_IMPLEMENTATION_DONE\n" % g)
            f.write('#include "wrinkle/wrinkle.h"\n#include "wrinkle/tfw.h"\n')
        return os.path.relpath(path, self.dir)


def decl_part(text, pos):
    """True when offset pos lies before the header's '#ifdef WRINKLE_IMPLEMENTATION' line."""
    k = text.find("\n#ifdef WRINKLE_IMPLEMENTATION")
    return k < 0 or pos < k


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--list", default="tests/mutants.txt")
    ap.add_argument("--only", default="")
    ap.add_argument("--scratch", default=os.path.join(os.environ.get("TMPDIR", "/tmp"),
                                                      "wrinkle-mutate-%d" % os.getuid()))
    ap.add_argument("--keep-going", action="store_true", help="run every test of the filter (no --fail-fast)")
    ap.add_argument("-j", type=int, default=2)
    ap.add_argument("--report", default="", help="also write the table to this file")
    ap.add_argument("--anchors", action="store_true", help="only check that every anchor is found exactly once")
    args = ap.parse_args()
    src = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
    muts = parse_list(os.path.join(src, args.list))
    if args.only:
        want = set(args.only.split(","))
        muts = [m for m in muts if m.id in want]
        if not muts:
            log("mutate: no mutant named %s" % args.only)
            return 2
    if args.anchors:
        bad = 0
        for m in muts:
            try:
                with open(os.path.join(src, m.header), encoding="utf-8") as f:
                    n = len(find_anchor(f.read(), m.anchor))
            except OSError:
                n = -1
            if n != 1:
                bad += 1
                log("  %-9s %-34s %s:%d" % ("STALE" if n <= 0 else "AMBIGUOUS", m.id, args.list, m.lineno))
        log("mutate: %d mutants, %d anchors not found exactly once" % (len(muts), bad))
        return 1 if bad else 0
    scratch = os.path.abspath(args.scratch)
    if scratch == src or src.startswith(scratch + os.sep) or scratch.startswith(src + os.sep):
        log("mutate: scratch directory %s must be outside the tree %s" % (scratch, src))
        return 2
    if os.path.exists(scratch):
        # keep the cached objects, refresh the sources
        for d in ("include", "tests", "drivers", "validation", "examples"):
            shutil.rmtree(os.path.join(scratch, d), ignore_errors=True)
    T = Tree(src, scratch, args.j)
    T.copy()
    mods = T.modules()
    hh = T.headers_hash()
    env = dict(os.environ)
    env.setdefault("ASAN_OPTIONS", "detect_leaks=1:abort_on_error=0")
    env.setdefault("UBSAN_OPTIONS", "print_stacktrace=1:halt_on_error=1")
    for k in ("OMP_THREAD_LIMIT", "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS"):
        env.setdefault(k, "1")
    t_start = time.time()

    # -- objects built once ---------------------------------------------------------------------
    def o(name):
        return os.path.relpath(os.path.join(T.obj, name), T.dir)

    tests = sorted(f for f in os.listdir(os.path.join(T.dir, "tests")) if f.startswith("test_") and f.endswith(".c"))
    libs = sorted(f for f in os.listdir(os.path.join(T.dir, "drivers", "lib")) if f.endswith(".c") and f != "impl.c")
    all_valids = sorted({v for m in muts for v in m.valids})
    for v in all_valids:
        if not os.path.isfile(os.path.join(T.dir, "validation", "validate_%s.c" % v)):
            log("mutate: no validation/validate_%s.c (named by a mutant)" % v)
            return 2

    def fixed_objects(tag):
        """test/lib/validator objects; tag '' = from pristine headers (cached by hash)."""
        jobs = []
        for t in tests:
            jobs.append((TEST_FLAGS, "tests/" + t, o("%st_%s.o" % (tag, t[:-2]))))
        for l in libs:
            jobs.append((TEST_FLAGS, "drivers/lib/" + l, o("%sls_%s.o" % (tag, l[:-2]))))
            if all_valids:
                jobs.append((VALID_FLAGS, "drivers/lib/" + l, o("%slv_%s.o" % (tag, l[:-2]))))
        for v in all_valids:
            jobs.append((VALID_FLAGS, "validation/validate_%s.c" % v, o("%sv_%s.o" % (tag, v))))
        return jobs

    stamp = os.path.join(T.obj, "fixed.stamp")
    srcs_hash = hashlib.sha1()
    for t in tests + ["../drivers/lib/" + l for l in libs] + ["../validation/validate_%s.c" % v for v in all_valids]:
        with open(os.path.join(T.dir, "tests", t), "rb") as f:
            srcs_hash.update(f.read())
    key = hh + srcs_hash.hexdigest()[:12] + ",".join(all_valids)
    if not (os.path.exists(stamp) and open(stamp).read() == key):
        log("mutate: building the test, helper and validator objects once (%d units)" % len(fixed_objects("")))
        err = T.compile_many(fixed_objects(""))
        if err:
            log("mutate: pristine tree does not build: " + err)
            return 2
        with open(stamp, "w") as f:
            f.write(key)

    def rest_objects(mod, flavour):
        """impl unit without module mod (cached per headers hash)."""
        flags = TEST_FLAGS if flavour == "s" else VALID_FLAGS
        obj = o("rest_%s_%s_%s.o" % (flavour, mod.lower(), hh))
        if not os.path.exists(os.path.join(T.dir, obj)):
            srcu = T.unit_source("rest_" + mod.lower(), [mod])
            err = T.compile_many([(flags, srcu, obj)])
            if err:
                return None, err
        return obj, None

    def module_unit(mod, flavour, suffix):
        flags = TEST_FLAGS if flavour == "s" else VALID_FLAGS
        others = [g for g in set(mods.values()) if g not in (mod, "CORE")]
        srcu = T.unit_source("only_" + mod.lower(), others)
        obj = o("only_%s_%s.o" % (flavour, suffix))
        err = T.compile_many([(flags, srcu, obj)])
        return obj, err

    def link(objs, out, timeout=300):
        r = T.run(["nice", "cc"] + (SAN if "tests" in out else []) + ["-Wl,--allow-multiple-definition"] + objs +
                  ["-o", out] + LIBS + (["-lcriterion"] if "tests" in out else []), timeout=timeout)
        return None if r.returncode == 0 else (r.stdout.strip().split("\n")[-1] if r.stdout else "link failed")

    def build(mod, mut_decl, tag):
        """Builds bin_tests and the validators for the current (possibly mutated) headers."""
        tests_bin, vbins = o(tag + "tests"), {}
        if mut_decl or mod == "CORE":
            # everything that includes the headers is rebuilt
            err = T.compile_many(fixed_objects(tag + "x") +
                                 [(TEST_FLAGS, "tests/impl.c", o(tag + "x_impl_s.o"))] +
                                 ([(VALID_FLAGS, "drivers/lib/impl.c", o(tag + "x_impl_v.o"))] if all_valids else []))
            if err:
                return None, None, err
            tobjs = [o("%sxt_%s.o" % (tag, t[:-2])) for t in tests] + [o("%sxls_%s.o" % (tag, l[:-2])) for l in libs] + \
                [o(tag + "x_impl_s.o")]
            vlib = [o("%sxlv_%s.o" % (tag, l[:-2])) for l in libs] + [o(tag + "x_impl_v.o")]
            vpre = tag + "xv_"
        else:
            rs, err = rest_objects(mod, "s")
            if err:
                return None, None, err
            us, err = module_unit(mod, "s", tag)
            if err:
                return None, None, err
            tobjs = [o("t_%s.o" % t[:-2]) for t in tests] + [o("ls_%s.o" % l[:-2]) for l in libs] + [us, rs]
            vlib = []
            if all_valids:
                rv, err = rest_objects(mod, "v")
                if err:
                    return None, None, err
                uv, err = module_unit(mod, "v", tag)
                if err:
                    return None, None, err
                vlib = [o("lv_%s.o" % l[:-2]) for l in libs] + [uv, rv]
            vpre = "v_"
        err = link(tobjs, tests_bin)
        if err:
            return None, None, err
        for v in all_valids:
            vb = o(tag + "validate_" + v)
            err = link([o("%s%s.o" % (vpre, v))] + vlib, vb)
            if err:
                return None, None, err
            vbins[v] = vb
        return tests_bin, vbins, None

    def run_tests(binary, filt, timeout):
        cmd = ["nice", binary, "--jobs", str(args.j), "--short-filename", "--ascii"]
        if not args.keep_going:
            cmd.append("--fail-fast")
        if filt and filt != "*":
            cmd += ["--filter", filt]
        try:
            r = T.run(cmd, timeout=timeout, env=env)
        except subprocess.TimeoutExpired:
            return False, "timeout after %.0f s" % timeout, None
        out = r.stdout or ""
        syn = [ln for ln in out.split("\n") if "Synthesis" in ln]
        m = re.search(r"Tested: (\d+)", syn[-1]) if syn else None
        ntests = int(m.group(1)) if m else None
        if r.returncode == 0 and m and ntests > 0:
            return True, syn[-1].strip(), ntests
        fail = [ln for ln in out.split("\n") if re.search(r"\[(FAIL|----)\]|CRASH|ERROR|runtime error|Assertion", ln)]
        first = fail[0].strip() if fail else (syn[-1].strip() if syn else "exit %d" % r.returncode)
        return False, first[:200], ntests

    def run_valid(vbin, name, resdir, timeout):
        os.makedirs(os.path.join(T.dir, resdir), exist_ok=True)
        e = dict(env)
        e["WRINKLE_RESULTS_DIR"] = os.path.abspath(os.path.join(T.dir, resdir))
        t0 = time.time()
        try:
            r = T.run(["nice", vbin], timeout=timeout, env=e)
        except subprocess.TimeoutExpired:
            return None, "timeout after %.0f s" % timeout, time.time() - t0
        rows = {}
        for fn in os.listdir(os.path.join(T.dir, resdir)):
            if fn.endswith(".json"):
                try:
                    with open(os.path.join(T.dir, resdir, fn)) as f:
                        d = json.load(f)
                except (OSError, ValueError):
                    continue
                for q in d.get("quantities", []):
                    rows[d.get("case", fn) + ": " + q.get("name", "?")] = q.get("pass")
        return (r.returncode, rows), "", time.time() - t0

    # -- pristine baseline ------------------------------------------------------------------------
    log("mutate: %d mutants from %s; scratch %s" % (len(muts), args.list, scratch))
    filt_needed = sorted({m.filter for m in muts})
    some_mod = None
    for m in muts:
        if m.header in mods:
            some_mod = mods[m.header]
            break
    tb, vb, err = build(some_mod or "CORE", some_mod is None, "p_")
    if err:
        log("mutate: pristine tree does not build: " + err)
        return 2
    # one pristine run of every test the filters select (the union is usually the whole suite): if it
    # passes, every filter passes; its time bounds each mutant's run (timeout = 3x + 30 s)
    base_t, base_v = {}, {}
    union = "*" if "*" in filt_needed else "@(%s)" % "|".join(f[2:-3] if f.startswith("@(") and f.endswith(")/*")
                                                            else f for f in filt_needed)
    if "/" in union.replace(")/*", "") or not all(f.endswith("/*") for f in filt_needed if f != "*"):
        union = "*"
    elif union != "*":
        union += "/*"
    t0 = time.time()
    ok, msg, n = run_tests(tb, union, 3600)
    t_all = time.time() - t0
    if not ok:
        log("mutate: pristine tree fails (%s): %s" % (union, msg))
        return 2
    log("  pristine: %d tests (%s) pass, %.1f s" % (n, union, t_all))
    for filt in filt_needed:
        base_t[filt] = t_all
    for v in all_valids:
        res, msg, secs = run_valid(vb[v], v, os.path.join("build", "mutate", "res_pristine_" + v), 1800)
        if res is None:
            log("mutate: pristine validation %s: %s" % (v, msg))
            return 2
        base_v[v] = (res, secs)
        log("  pristine validate_%-30s exit %d, %d rows (%d pass) %6.1f s" %
            (v, res[0], len(res[1]), sum(1 for x in res[1].values() if x is True), secs))

    # -- mutants ----------------------------------------------------------------------------------
    for k, m in enumerate(muts):
        t0 = time.time()
        if m.header not in T.pristine:
            m.status, m.detail = "STALE", "no header " + m.header
        else:
            text = T.pristine[m.header]
            hits = find_anchor(text, m.anchor)
            if not hits:
                m.status, m.detail = "STALE", "anchor not found"
            elif len(hits) > 1:
                m.status, m.detail = "AMBIGUOUS", "anchor found %d times" % len(hits)
            else:
                start, end = hits[0]
                mtext = apply_mutant(text, m, start, end)
                T.write(m.header, mtext)
                try:
                    tb, vb, err = build(mods.get(m.header, "CORE"), decl_part(text, start), "m_")
                    if err:
                        m.status, m.detail = "NOBUILD", err[:200]
                    else:
                        ok, msg, n = run_tests(tb, m.filter, 3 * base_t[m.filter] + 30)
                        if not ok:
                            m.status, m.detail = "KILLED", "unit: " + msg
                        else:
                            for v in m.valids:
                                res, msg, _ = run_valid(vb[v], v, os.path.join("build", "mutate", "res_m_" + v),
                                                        3 * base_v[v][1] + 30)
                                shutil.rmtree(os.path.join(T.dir, "build", "mutate", "res_m_" + v), ignore_errors=True)
                                if res is None:
                                    m.status, m.detail = "KILLED", "validate_%s: %s" % (v, msg)
                                    break
                                (brc, brows), (rc, rows) = base_v[v][0], res
                                lost = [q for q, p in brows.items() if p is True and rows.get(q) is not True]
                                if rc != brc and rc not in (0, 1) or (rc != 0 and brc == 0 and not lost):
                                    m.status, m.detail = "KILLED", "validate_%s: exit %d (pristine %d)" % (v, rc, brc)
                                    break
                                if lost:
                                    m.status, m.detail = "KILLED", "validate_%s: %d row(s) now miss: %s" % (
                                        v, len(lost), lost[0][:120])
                                    break
                            else:
                                m.status, m.detail = "SURVIVED", "%s passed (%s)" % (
                                    m.filter, ", ".join(m.valids) if m.valids else "no validations")
                finally:
                    T.restore(m.header)
        m.seconds = time.time() - t0
        log("[%2d/%d] %-9s %-34s %5.1f s  %s" % (k + 1, len(muts), m.status, m.id, m.seconds, m.detail))

    # -- report -----------------------------------------------------------------------------------
    counts = {}
    for m in muts:
        counts[m.status] = counts.get(m.status, 0) + 1
    lines = ["", "mutate: %d mutants: %s (%.0f s)" % (len(muts), ", ".join("%s %d" % (s, counts[s]) for s in
                                                                           sorted(counts)), time.time() - t_start)]
    for s in ("SURVIVED", "STALE", "AMBIGUOUS", "NOBUILD"):
        for m in muts:
            if m.status == s:
                lines.append("  %-9s %-34s %s:%d  %s" % (s, m.id, args.list, m.lineno, m.detail))
    log("\n".join(lines))
    if args.report:
        with open(args.report, "w") as f:
            for m in muts:
                f.write("%s\t%s\t%s\t%.1f\t%s\n" % (m.id, m.status, m.header, m.seconds, m.detail))
    return 0 if all(m.status == "KILLED" for m in muts) else 1


if __name__ == "__main__":
    sys.exit(main())
