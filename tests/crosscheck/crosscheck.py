#!/usr/bin/env python3
"""crosscheck.py - render the same scenes in fogrt and in Mitsuba 3 and compare them.

    python3 tests/crosscheck/crosscheck.py --fogrt build/fogrt --out build/crosscheck
    make crosscheck                    (the same, with the venv and the fogrt build)

Optional and never part of `make test`. Without mitsuba importable, the script makes its own
virtual environment (--venv, default build/crosscheck-venv) with `pip install mitsuba numpy`
and runs itself again inside it.

For every scene of scenes.py it writes a COLLADA file and a CS184 camera file for fogrt and
builds the matching Mitsuba scene dict (volpath, or volpathmis for chromatic fog; homogeneous
medium with hg phase, dielectric glass, the same camera, lights and fog). Each renderer renders the scene as --batches (4)
independent batches (different seeds, the same spp) of about --budget / 4 seconds each. The
spread of the batches gives a per-pixel noise estimate of their mean, from which every
comparison gets its noise level:

  - mean ratio fogrt / Mitsuba per channel, and its z-score;
  - D = sum (F - M)^2 / sum ref^2 (ref = (F + M) / 2): the relative MSE between the two
    images, next to E = sum (var F + var M) / sum ref^2, its value if they differed by
    noise only (D / E near 1: agreement);
  - the worst 8x8 block: the block whose mean differs most in units of its noise (z), and
    its ratio; with 192 blocks, |z| up to about 3.5 is noise (blocks darker than 5% of the
    mean block are skipped);
  - each renderer's own relative MSE (sum var / sum ref^2) scaled to an equal time of
    10 CPU seconds (and 10 wall seconds; relative MSE falls as 1 / time for both), and the
    spp and seconds it took. CPU time is the fairer measure on a shared machine: fogrt's is
    its process's user + system time, Mitsuba's the Python process's (its render threads).

With --mitsuba-long S, Mitsuba also renders each scene alone for S more seconds (batches of
64 spp, other seeds), and fogrt's channel means are compared with that longer estimate: for
scenes where a short Mitsuba run's noise is heavy-tailed (point and spot lights in fog, whose
light sampled from fog vertices near the lamp has no finite variance), most short runs miss
the rare large samples and come out low.

The scenes named single_* have no geometry and single scattering only (fogrt -m 1, Mitsuba
max_depth 2): for them a quadrature of the single-scattering integral is the reference, and
each renderer is also measured against it.

Outputs in --out: results.json, results.md (the tables of docs/validation.md), and per scene
<scene>_side.png (fogrt left, Mitsuba right, same exposure), the .dae and camera file.
"""
import argparse
import json
import math
import os
import re
import resource
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

LLVM_CANDIDATES = [
    "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1",
    "/usr/lib/llvm-19/lib/libLLVM.so.1",
    "/usr/lib/llvm-19/lib/libLLVM-19.so",
    "/usr/lib/x86_64-linux-gnu/libLLVM-19.so",
]


# ---------------------------------------------------------------------------------------
# The virtual environment
# ---------------------------------------------------------------------------------------
def ensure_environment(venv):
    try:
        import mitsuba  # noqa: F401
        import numpy  # noqa: F401
        return
    except ImportError:
        pass
    py = os.path.join(venv, "bin", "python")
    if os.path.abspath(sys.prefix) == os.path.abspath(venv):
        sys.exit("crosscheck: mitsuba or numpy missing in %s (pip install mitsuba numpy failed?)" % venv)
    if os.path.exists(py) and subprocess.run([py, "-c", "import mitsuba, numpy"], capture_output=True).returncode == 0:
        os.execv(py, [py] + sys.argv)
    if not os.path.exists(py):
        print("crosscheck: making the virtual environment %s" % venv, flush=True)
        subprocess.check_call([sys.executable, "-m", "venv", venv])
    print("crosscheck: pip install mitsuba numpy (into %s)" % venv, flush=True)
    subprocess.check_call([py, "-m", "pip", "install", "-q", "mitsuba", "numpy"])
    os.execv(py, [py] + sys.argv)


def choose_variant(want):
    """llvm_ad_rgb when it works (it needs LLVM >= 16: Debian's libllvm19), else scalar_rgb.
    The llvm variant is tried in a child process, since a bad libLLVM can abort."""
    if want == "scalar":
        return "scalar_rgb", None
    env = dict(os.environ)
    if "DRJIT_LIBLLVM_PATH" not in env:
        for c in LLVM_CANDIDATES:
            if os.path.exists(c):
                env["DRJIT_LIBLLVM_PATH"] = c
                break
    probe = ("import mitsuba as mi; mi.set_variant('llvm_ad_rgb');"
             "s = mi.load_dict({'type':'scene','integrator':{'type':'path'},'sensor':{'type':'perspective',"
             "'film':{'type':'hdrfilm','width':8,'height':8}},'e':{'type':'constant'}});"
             "print(float(mi.render(s, spp=2).array[0]))")
    try:
        r = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True, text=True, timeout=300)
        ok = r.returncode == 0 and r.stdout.strip() != ""
    except subprocess.TimeoutExpired:
        ok = False
    if ok:
        if "DRJIT_LIBLLVM_PATH" in env:
            os.environ["DRJIT_LIBLLVM_PATH"] = env["DRJIT_LIBLLVM_PATH"]
        return "llvm_ad_rgb", env.get("DRJIT_LIBLLVM_PATH")
    if want == "llvm":
        sys.exit("crosscheck: --variant llvm requested but llvm_ad_rgb does not work here")
    print("crosscheck: llvm_ad_rgb does not work here (install Debian's libllvm19); using scalar_rgb", flush=True)
    return "scalar_rgb", None


# ---------------------------------------------------------------------------------------
# fogrt
# ---------------------------------------------------------------------------------------
def read_pfm(path):
    import numpy as np
    with open(path, "rb") as f:
        kind = f.readline().strip()
        w, h = (int(x) for x in f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    if kind != b"PF":
        raise ValueError("%s: not an RGB PFM" % path)
    return data.reshape(h, w, 3)[::-1].astype(np.float64)     # PFM rows go bottom-up


def run_fogrt(exe, dae, cam, args, width, height, spp, seed, out, threads):
    cmd = [exe, "-t", str(threads), "-s", str(spp), "-r", str(width), str(height), "-c", cam,
           "--seed", str(seed), "-f", out] + args + [dae]
    t0 = time.time()
    c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run(cmd, capture_output=True, text=True)
    c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    wall = time.time() - t0
    cpu = (c1.ru_utime - c0.ru_utime) + (c1.ru_stime - c0.ru_stime)
    if r.returncode != 0:
        raise RuntimeError("fogrt failed (%d): %s\n%s" % (r.returncode, " ".join(cmd), r.stderr.strip()[-2000:]))
    m = re.search(r"wrote .*?: ([0-9.]+) spp in ([0-9.]+) s", r.stderr)
    seconds = float(m.group(2)) if m else wall      # render time without loading, else wall time
    return read_pfm(out), seconds, cpu, " ".join(os.path.relpath(c) if os.path.exists(c) else c for c in cmd)


def render_fogrt(exe, sc, dae, cam, width, height, budget, workdir, threads, batches, tag="fogrt"):
    """Independent batches (seeds 1..batches) of the same spp, about budget / batches seconds each."""
    args = sc["fogrt_args"]
    _, t, _, _ = run_fogrt(exe, dae, cam, args, width, height, 8, 99, os.path.join(workdir, "cal.pfm"), threads)
    spp = max(4, int(round(8 * budget / batches / max(t, 1e-3))))
    halves, secs, cpu, cmd = [], 0.0, 0.0, None
    for seed in range(1, batches + 1):
        img, t, c, cmd = run_fogrt(exe, dae, cam, args, width, height, spp, seed,
                                   os.path.join(workdir, "%s_%s_%d.pfm" % (sc["name"], tag, seed)), threads)
        halves.append(img)
        secs += t
        cpu += c
    return halves, batches * spp, secs, cpu, cmd


# ---------------------------------------------------------------------------------------
# Mitsuba 3
# ---------------------------------------------------------------------------------------
def render_mitsuba(mi, sc, width, height, budget, workdir, batches):
    import numpy as np
    import scenes
    t0 = time.time()
    scene = mi.load_dict(scenes.mitsuba_dict(mi, sc, width, height, workdir))
    np.array(mi.render(scene, spp=1, seed=7))                     # JIT compile (llvm), not timed
    t_setup = time.time() - t0
    t0 = time.time()
    np.array(mi.render(scene, spp=4, seed=8))
    per_spp = max((time.time() - t0) / 4, 1e-4)
    spp_half = max(4, int(round(budget / batches / per_spp)))
    pass_spp = max(1, min(64, int(round(1.0 / per_spp)), spp_half))
    n_pass = max(1, int(round(spp_half / pass_spp)))
    halves, secs, cpu = [], 0.0, 0.0
    for h in range(batches):
        acc = np.zeros((height, width, 3))
        t0, c0 = time.time(), time.process_time()
        for k in range(n_pass):
            acc += np.array(mi.render(scene, spp=pass_spp, seed=1000 * (h + 1) + k), dtype=np.float64)
        secs += time.time() - t0
        cpu += time.process_time() - c0
        halves.append(acc / n_pass)
    return halves, batches * n_pass * pass_spp, secs, cpu, t_setup


def long_mitsuba(mi, sc, width, height, seconds, workdir):
    """Mitsuba alone for about `seconds`, in batches of 64 spp: the per-channel image mean,
    its standard error from the batches' spread, and the samples per pixel."""
    import numpy as np
    import scenes
    scene = mi.load_dict(scenes.mitsuba_dict(mi, sc, width, height, workdir))
    means, t0 = [], time.time()
    while time.time() - t0 < seconds or len(means) < 2:
        img = np.array(mi.render(scene, spp=64, seed=50000 + len(means)), dtype=np.float64)
        means.append(img.mean((0, 1)))
    m = np.array(means)
    return m.mean(0), m.std(0, ddof=1) / math.sqrt(len(means)), 64 * len(means)


# ---------------------------------------------------------------------------------------
# The closed-form (quadrature) reference for single scattering without geometry
# ---------------------------------------------------------------------------------------
def single_scatter_reference(sc, width, height, sub=3, n_theta=1024, window=None):
    """L = int_0^inf sigma_s e^{-sigma_t t} p(cos) I(x) e^{-sigma_t r} / r^2 dt along each
    camera ray, with the substitution t = Delta + h tan(theta), for which dt / r^2 = dtheta / h
    and the cosine between the light's travel direction and the ray's reverse is -sin(theta).
    Midpoint rule in theta, sub x sub samples per pixel (the box filter). window = (x0, x1,
    y0, y1) computes only those pixels (the rest stay 0)."""
    import numpy as np
    cam, fog, light = sc["camera"], sc["fog"], sc["lights"][0]
    pos, tgt = np.array(cam["position"], float), np.array(cam["target"], float)
    fwd = (tgt - pos) / np.linalg.norm(tgt - pos)
    right = np.cross(fwd, cam["up"]); right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    ty = math.tan(math.radians(cam["vfov"]) / 2); tx = ty * width / height
    P = np.array(light["position"], float)
    g, st = fog["g"], fog["sigma_t"]
    ss = st * np.array(fog["albedo"], float)
    I = np.array(light["intensity"], float)
    if light["type"] == "spot":
        axis = np.array(light["direction"], float); axis /= np.linalg.norm(axis)
        cut, beam = math.radians(light["cutoff_deg"]), math.radians(light["beam_deg"])
    out = np.zeros((height, width, 3))
    u = (np.arange(n_theta) + 0.5) / n_theta
    x0, x1, y0, y1 = window or (0, width, 0, height)
    cols = x1 - x0
    for y in range(y0, y1):
        px = (np.arange(x0, x1)[:, None] + (np.arange(sub)[None, :] + 0.5) / sub).reshape(-1)
        py = y + (np.arange(sub) + 0.5) / sub
        X, Y = np.meshgrid(px, py)
        X, Y = X.reshape(-1), Y.reshape(-1)
        sx = (2 * X / width - 1) * tx
        sy = (1 - 2 * Y / height) * ty
        d = fwd[None] + sx[:, None] * right[None] + sy[:, None] * up[None]
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        oc = P[None] - pos[None]
        delta = (oc * d).sum(1)
        h = np.linalg.norm(np.cross(oc, d), axis=1)
        t_lo, t_hi = np.zeros(len(d)), np.full(len(d), np.inf)
        if light["type"] == "spot":     # integrate only over the part of the ray inside the cone
            t_lo, t_hi = cone_interval(pos - P, d, axis, cut, t_far=80.0 / st)
        th0 = np.arctan2(t_lo - delta, h)
        th1 = np.where(np.isfinite(t_hi), np.arctan2(t_hi - delta, h), 0.5 * math.pi)
        th1 = np.maximum(th1, th0)
        th = th0[:, None] + (th1 - th0)[:, None] * u[None]
        dth = (th1 - th0) / n_theta
        t = delta[:, None] + h[:, None] * np.tan(th)
        r = h[:, None] / np.cos(th)
        cos_s = -np.sin(th)
        phase = (1 - g * g) / (4 * math.pi * (1 + g * g - 2 * g * cos_s) ** 1.5)
        f = np.exp(-st * (t + r)) * phase / h[:, None]
        if light["type"] == "spot":
            x = pos[None, None] + t[..., None] * d[:, None, :]
            v = x - P[None, None]
            ang = np.arccos(np.clip((v * axis).sum(-1) / np.linalg.norm(v, axis=-1), -1, 1))
            f = f * np.clip((cut - ang) / (cut - beam), 0, 1)
        val = f.sum(1) * dth
        val = val.reshape(sub, cols, sub).mean(axis=(0, 2))
        out[y, x0:x1] = val[:, None] * ss[None] * I[None]
    return out


def cone_interval(w, d, axis, cut, t_far):
    """Per ray o + t d (w = o - apex, t >= 0), the interval of t inside the forward cone of
    half-angle cut (< 90 degrees) around axis: convex, so one interval. Its ends are among
    0, the roots of (x.a)^2 = cos^2(cut) |x|^2, and t_far; the midpoints decide. Rays that
    miss get an empty interval."""
    import numpy as np
    c2 = math.cos(cut) ** 2
    da, wa = d @ axis, w @ axis
    A = da * da - c2
    B = da * wa - c2 * (d @ w)
    C = wa * wa - c2 * (w @ w)
    disc = B * B - A * C
    q = np.sqrt(np.maximum(disc, 0))
    with np.errstate(divide="ignore", invalid="ignore"):
        r1 = np.where((disc >= 0) & (A != 0), (-B - q) / A, np.nan)
        r2 = np.where((disc >= 0) & (A != 0), (-B + q) / A, np.nan)
    n = len(d)
    cand = np.stack([np.zeros(n), r1, r2, np.full(n, t_far)], 1)
    cand = np.where(np.isfinite(cand), np.clip(cand, 0, t_far), 0)
    cand.sort(1)
    lo, hi = np.full(n, np.inf), np.full(n, -np.inf)
    for k in range(3):
        a, b = cand[:, k], cand[:, k + 1]
        m = 0.5 * (a + b)
        x = w[None] + m[:, None] * d
        xa = x @ axis
        inside = (b > a) & (xa >= 0) & (xa * xa >= c2 * (x * x).sum(1))
        lo = np.where(inside, np.minimum(lo, a), lo)
        hi = np.where(inside, np.maximum(hi, b), hi)
    empty = ~(hi > lo)
    return np.where(empty, 0.0, lo), np.where(empty, 0.0, hi)


def near_light_check(sc, width, height, F, vF, M, vM, r_in=1.0, r_out=4.0):
    """The pixels left out of the other numbers, 1 to 4 pixels from the light's image, where
    the single-scattering radiance grows like 1 / (distance of the ray from the light):
    both renderers against a finer quadrature (12 x 12 samples per pixel)."""
    import numpy as np
    lx, ly = light_pixel(sc, width, height)
    win = (max(0, int(lx - r_out - 1)), min(width, int(lx + r_out + 2)),
           max(0, int(ly - r_out - 1)), min(height, int(ly + r_out + 2)))
    Q = single_scatter_reference(sc, width, height, sub=12, n_theta=2048, window=win)
    yy, xx = np.mgrid[0:height, 0:width]
    rr = np.hypot(xx + 0.5 - lx, yy + 0.5 - ly)
    ring = (rr >= r_in) & (rr < r_out)
    q = Q[ring].sum()
    out = {"pixels": int(ring.sum()), "quadrature_sum": float(q)}
    for key, X, v in (("fogrt", F, vF), ("mitsuba", M, vM)):
        out[key] = {"ratio": float(X[ring].sum() / q), "z": float((X[ring].sum() - q) / math.sqrt(v[ring].sum()))}
    return out


def light_pixel(sc, width, height):
    cam, P = sc["camera"], sc["lights"][0]["position"]
    import numpy as np
    pos, tgt = np.array(cam["position"], float), np.array(cam["target"], float)
    fwd = (tgt - pos) / np.linalg.norm(tgt - pos)
    right = np.cross(fwd, cam["up"]); right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    v = np.array(P, float) - pos
    z = v @ fwd
    ty = math.tan(math.radians(cam["vfov"]) / 2); tx = ty * width / height
    return ((v @ right) / z / tx + 1) * width / 2, (1 - (v @ up) / z / ty) * height / 2


# ---------------------------------------------------------------------------------------
# Statistics
# ---------------------------------------------------------------------------------------
def compare(X, varX, sumvarX, Y, varY, sumvarY, mask, block=8):
    """X against Y (Y may be a noise-free reference, varY = 0). varX: per-pixel, per-channel
    variance of X; sumvarX: per-pixel variance of the sum of X's three channels."""
    import numpy as np
    m = mask[..., None] * np.ones(3)
    ref = 0.5 * (X + Y) if np.any(varY) else Y
    den = (ref ** 2 * m).sum()
    res = {}
    n = m.sum() / 3
    mx, my = (X * m).sum((0, 1)) / n, (Y * m).sum((0, 1)) / n
    vx, vy = (varX * m).sum((0, 1)) / n ** 2, (varY * m).sum((0, 1)) / n ** 2
    res["ratio"] = (mx / my).tolist()
    res["ratio_sigma"] = (mx / my * np.sqrt(vx / mx ** 2 + vy / my ** 2)).tolist()
    res["ratio_z"] = ((mx - my) / np.sqrt(vx + vy)).tolist()
    res["relmse_between"] = float((((X - Y) ** 2) * m).sum() / den)
    res["relmse_noise"] = float(((varX + varY) * m).sum() / den)
    H, W = X.shape[:2]
    # blocks darker than 5% of the mean block carry no information (a sub-pixel sliver of a
    # cone edge, say) and are skipped
    dim = 0.05 * (Y.sum(2) * mask).sum() / (H * W / block ** 2)
    best = None
    for by in range(0, H - block + 1, block):
        for bx in range(0, W - block + 1, block):
            sl = (slice(by, by + block), slice(bx, bx + block))
            mm = mask[sl]
            if mm.sum() < block * block // 2:
                continue
            sx, sy = (X[sl].sum(2) * mm).sum(), (Y[sl].sum(2) * mm).sum()
            v = ((sumvarX[sl] + sumvarY[sl]) * mm).sum()
            if v <= 0 or sy <= dim:
                continue
            z = (sx - sy) / math.sqrt(v)
            if best is None or abs(z) > abs(best[0]):
                best = (z, sx / sy, bx, by)
    res["worst_block"] = {"z": best[0], "ratio": best[1], "x": best[2], "y": best[3], "size": block}
    return res


def batch_stats(batches):
    """Mean of K independent equal batches, its per-pixel per-channel variance and the
    variance of its channel sum, each estimated from the spread of the batches (K - 1
    degrees of freedom per pixel)."""
    import numpy as np
    B = np.stack(batches)
    K = len(batches)
    mean = B.mean(0)
    var = ((B - mean) ** 2).sum(0) / (K - 1) / K
    s = B.sum(3)
    svar = ((s - s.mean(0)) ** 2).sum(0) / (K - 1) / K
    return mean, var, svar


def write_side_by_side(mi, path, images, scale):
    import numpy as np
    gap = np.ones((images[0].shape[0], 4, 3)) * 0.25
    row = []
    for k, im in enumerate(images):
        if k:
            row.append(gap)
        row.append(im * scale)
    a = np.concatenate(row, axis=1)
    a = np.repeat(np.repeat(a, 2, axis=0), 2, axis=1)      # 2x for viewing
    mi.util.write_bitmap(path, a.astype(np.float32), write_async=False)


# ---------------------------------------------------------------------------------------
# main
# ---------------------------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--fogrt", default="build/fogrt", help="the fogrt command (default build/fogrt)")
    ap.add_argument("--out", default="build/crosscheck", help="output directory (default build/crosscheck)")
    ap.add_argument("--venv", default="build/crosscheck-venv", help="virtual environment (default build/crosscheck-venv)")
    ap.add_argument("--budget", type=float, default=24.0,
                    help="seconds per renderer per scene, both halves together (default 24)")
    ap.add_argument("--quick", action="store_true", help="budget 2 s: a smoke test, not a measurement")
    ap.add_argument("--size", type=int, nargs=2, default=(128, 96), metavar=("W", "H"))
    ap.add_argument("--scenes", default="", help="comma-separated scene names (default: all)")
    ap.add_argument("--variant", choices=("auto", "llvm", "scalar"), default="auto")
    ap.add_argument("--threads", type=int, default=2, help="fogrt threads (default 2)")
    ap.add_argument("--fogrt-base", default="",
                    help="another fogrt command (another commit's build) rendered after --fogrt on every scene of the run, "
                         "with the same batches and budget; its equal-time error ends the report")
    ap.add_argument("--batches", type=int, default=4,
                    help="independent batches per renderer, for the noise estimate (default 4)")
    ap.add_argument("--mitsuba-long", type=float, default=0.0, metavar="S",
                    help="also render Mitsuba alone for S seconds per scene and compare fogrt's channel means with it")
    a = ap.parse_args()
    ensure_environment(a.venv)
    import numpy as np
    import scenes
    if a.quick:
        a.budget = 2.0
    if a.batches < 2:
        sys.exit("crosscheck: --batches must be at least 2 (the noise estimate needs two)")
    for exe in [a.fogrt] + ([a.fogrt_base] if a.fogrt_base else []):
        if not os.access(exe, os.X_OK):
            sys.exit("crosscheck: %s is not an executable (make BUILD=... first)" % exe)
    variant, llvm = choose_variant(a.variant)
    import mitsuba as mi
    mi.set_variant(variant)
    W, H = a.size
    os.makedirs(a.out, exist_ok=True)
    todo = scenes.all_scenes()
    if a.scenes:
        names = a.scenes.split(",")
        unknown = [n for n in names if n not in [s["name"] for s in todo]]
        if unknown:
            sys.exit("crosscheck: --scenes: unknown scene(s) %s; known: %s"
                     % (", ".join(unknown), ", ".join(s["name"] for s in todo)))
        todo = [s for s in todo if s["name"] in names]
    print("crosscheck: Mitsuba %s, variant %s%s; %dx%d, %.0f s per renderer per scene"
          % (mi.__version__, variant, " (libLLVM %s)" % llvm if llvm else "", W, H, a.budget), flush=True)
    results = {"mitsuba": mi.__version__, "variant": variant, "llvm": llvm, "size": [W, H], "batches": a.batches,
               "budget": a.budget, "threads_fogrt": a.threads, "scenes": []}
    t_start = time.time()
    for sc in todo:
        t_scene = time.time()
        sc["fogrt_args"] = scenes.fogrt_args(sc)
        dae = os.path.join(a.out, sc["name"] + ".dae")
        cam = os.path.join(a.out, sc["name"] + ".cam")
        scenes.write_dae(sc, dae)
        scenes.write_camera(sc, W, H, cam)
        fh, f_spp, f_sec, f_cpu, f_cmd = render_fogrt(a.fogrt, sc, dae, cam, W, H, a.budget, a.out, a.threads, a.batches)
        if a.fogrt_base:
            bh, b_spp, b_sec, b_cpu, _ = render_fogrt(a.fogrt_base, sc, dae, cam, W, H, a.budget, a.out, a.threads,
                                                      a.batches, tag="base")
        mh, m_spp, m_sec, m_cpu, m_setup = render_mitsuba(mi, sc, W, H, a.budget, a.out, a.batches)
        F, vF, sF = batch_stats(fh)
        M, vM, sM = batch_stats(mh)
        np.savez_compressed(os.path.join(a.out, sc["name"] + "_images.npz"), fogrt=np.stack(fh), mitsuba=np.stack(mh))
        mask = np.ones((H, W), bool)
        if sc["analytic"]:
            lx, ly = light_pixel(sc, W, H)
            yy, xx = np.mgrid[0:H, 0:W]
            mask = (xx + 0.5 - lx) ** 2 + (yy + 0.5 - ly) ** 2 > 4.0 ** 2
        r = {"name": sc["name"], "title": sc["title"], "fog": sc["fog"], "fogrt_command": f_cmd,
             "fogrt": {"spp": f_spp, "seconds": f_sec, "cpu_seconds": f_cpu},
             "mitsuba": {"spp": m_spp, "seconds": m_sec, "cpu_seconds": m_cpu, "setup_seconds": m_setup},
             "masked_pixels": int((~mask).sum())}
        if a.fogrt_base:
            r["fogrt_base"] = {"spp": b_spp, "seconds": b_sec, "cpu_seconds": b_cpu}
        r["fogrt_vs_mitsuba"] = compare(F, vF, sF, M, vM, sM, mask)
        ref = 0.5 * (F + M)
        den = (ref ** 2 * mask[..., None]).sum()
        if sc["analytic"]:
            Q = single_scatter_reference(sc, W, H)
            np.save(os.path.join(a.out, sc["name"] + "_quadrature.npy"), Q)
            r["near_light"] = near_light_check(sc, W, H, F, vF, M, vM)
            r["fogrt_vs_quadrature"] = compare(F, vF, sF, Q, 0 * Q, 0 * sF, mask)
            r["mitsuba_vs_quadrature"] = compare(M, vM, sM, Q, 0 * Q, 0 * sM, mask)
            den = (Q ** 2 * mask[..., None]).sum()
        runs = [("fogrt", vF, f_sec, f_cpu), ("mitsuba", vM, m_sec, m_cpu)]
        if a.fogrt_base:
            runs.append(("fogrt_base", batch_stats(bh)[1], b_sec, b_cpu))
        for key, v, sec, cpu in runs:
            rel = float((v * mask[..., None]).sum() / den)
            r[key]["relmse"] = rel
            r[key]["relmse_10s"] = rel * sec / 10.0          # equal wall time (10 s)
            r[key]["relmse_10cpus"] = rel * cpu / 10.0       # equal CPU time (10 CPU seconds)
        scale = 0.18 / max(float((ref * mask[..., None]).mean()), 1e-9)
        imgs = [F, M] + ([Q] if sc["analytic"] else [])
        write_side_by_side(mi, os.path.join(a.out, sc["name"] + "_side.png"), imgs, scale)
        fm = r["fogrt_vs_mitsuba"]
        print("%-20s ratio %s (z %s)  D/E %.2f  worst block z %+.1f ratio %.3f  relMSE@10cpu-s fogrt %.2e mitsuba %.2e  [%.0f s]"
              % (sc["name"], " ".join("%.4f" % x for x in fm["ratio"]), " ".join("%+.1f" % z for z in fm["ratio_z"]),
                 fm["relmse_between"] / fm["relmse_noise"], fm["worst_block"]["z"], fm["worst_block"]["ratio"],
                 r["fogrt"]["relmse_10cpus"], r["mitsuba"]["relmse_10cpus"], time.time() - t_scene), flush=True)
        if "near_light" in r:
            nl = r["near_light"]
            print("%20s near the light (%d px, 1-4 px away): fogrt/quadrature %.4f (z %+.1f), Mitsuba/quadrature %.4f (z %+.1f)"
                  % ("", nl["pixels"], nl["fogrt"]["ratio"], nl["fogrt"]["z"], nl["mitsuba"]["ratio"], nl["mitsuba"]["z"]),
                  flush=True)
        if a.mitsuba_long > 0:
            lm, lse, lspp = long_mitsuba(mi, sc, W, H, a.mitsuba_long, a.out)
            fmean = (F * mask[..., None]).sum((0, 1)) / mask.sum()
            fse = np.sqrt((vF * mask[..., None]).sum((0, 1))) / mask.sum()
            r["mitsuba_long"] = {"spp": lspp, "mean": lm.tolist(), "se": lse.tolist(), "ratio": (fmean / lm).tolist(),
                                 "z": ((fmean - lm) / np.sqrt(fse ** 2 + lse ** 2)).tolist()}
            print("%20s Mitsuba alone, %d spp: fogrt / it %s (z %s)"
                  % ("", lspp, " ".join("%.4f" % x for x in r["mitsuba_long"]["ratio"]),
                     " ".join("%+.1f" % z for z in r["mitsuba_long"]["z"])), flush=True)
        for k in ("fogrt_vs_quadrature", "mitsuba_vs_quadrature"):
            if k in r:
                q = r[k]
                print("%20s %s ratio %s (z %s)  D/E %.2f  worst block z %+.1f ratio %.3f"
                      % ("", k.split("_")[0].ljust(7), " ".join("%.4f" % x for x in q["ratio"]),
                         " ".join("%+.1f" % z for z in q["ratio_z"]), q["relmse_between"] / q["relmse_noise"],
                         q["worst_block"]["z"], q["worst_block"]["ratio"]), flush=True)
        results["scenes"].append(r)
    results["seconds"] = time.time() - t_start
    with open(os.path.join(a.out, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
    with open(os.path.join(a.out, "results.md"), "w") as f:
        f.write(markdown(results))
    print("crosscheck: %d scenes in %.0f s -> %s" % (len(todo), results["seconds"], os.path.join(a.out, "results.md")))
    # Equal-time efficiency (make bench-mitsuba): relative MSE x CPU seconds of each
    # renderer (its own batch noise over the scene, the same denominator for both), and their
    # ratio; the goal is fogrt at or below 0.5x Mitsuba's on every scene.
    print("equal-time error: relMSE x CPU seconds (lower is better); goal fogrt/Mitsuba <= 0.5")
    print("%-20s %12s %12s %10s  %s" % ("scene", "fogrt", "Mitsuba", "ratio", "goal"))
    for r in results["scenes"]:
        fe = r["fogrt"]["relmse"] * r["fogrt"]["cpu_seconds"]
        me = r["mitsuba"]["relmse"] * r["mitsuba"]["cpu_seconds"]
        ratio = fe / me if me > 0 else float("inf")
        print("%-20s %12.3e %12.3e %10.3f  %s" % (r["name"], fe, me, ratio, "met" if ratio <= 0.5 else "NOT met"))
    if a.fogrt_base:
        # The same figure for the two fogrt builds, rendered alternately in this run: above 1,
        # --fogrt reaches a given error in less CPU time than --fogrt-base.
        print("this build against %s: relMSE x CPU seconds, base / this (above 1: this build is better)" % a.fogrt_base)
        for r in results["scenes"]:
            fe = r["fogrt"]["relmse"] * r["fogrt"]["cpu_seconds"]
            be = r["fogrt_base"]["relmse"] * r["fogrt_base"]["cpu_seconds"]
            print("%-20s %12.3e %12.3e %10.3f" % (r["name"], be, fe, be / fe if fe > 0 else float("inf")))


def verdict(c):
    z = max(abs(x) for x in c["ratio_z"])
    ok = z < 3.0 and abs(c["worst_block"]["z"]) < 4.5
    return "agree within noise" if ok else "DIFFER (|z| %.1f, worst block z %+.1f)" % (z, c["worst_block"]["z"])


def markdown(res):
    import scenes
    out = ["Mitsuba %s, variant `%s`; %dx%d pixels; about %.0f s per renderer per scene in %d batches; "
           "fogrt on %d threads; total %.0f s.\n"
           % (res["mitsuba"], res["variant"], res["size"][0], res["size"][1], res["budget"], res["batches"],
              res["threads_fogrt"], res["seconds"])]
    for r in res["scenes"]:
        fm = r["fogrt_vs_mitsuba"]
        out.append("### %s: %s\n" % (r["name"], r["title"]))
        if r["fog"]:
            out.append("Fog: sigma_t %s, albedo %s, g %+g. " % (scenes.sigma_text(r["fog"]),
                                                                ",".join("%g" % x for x in r["fog"]["albedo"]), r["fog"]["g"]))
        out.append("fogrt: `%s`\n" % r["fogrt_command"])
        if r["masked_pixels"]:
            out.append("(%d pixels within 4 pixels of the light's image are left out of the table; see below.)\n"
                       % r["masked_pixels"])
        out.append("| comparison | mean ratio R, G, B (+-1 sigma) | z of the ratio | relMSE between / from noise alone | worst 8x8 block: ratio, z | verdict |")
        out.append("| --- | --- | --- | --- | --- | --- |")
        rows = [("fogrt / Mitsuba", fm)]
        if "fogrt_vs_quadrature" in r:
            rows += [("fogrt / quadrature", r["fogrt_vs_quadrature"]), ("Mitsuba / quadrature", r["mitsuba_vs_quadrature"])]
        for name, c in rows:
            out.append("| %s | %s | %s | %.3g / %.3g (%.2f) | %.3f, %+.1f | %s |"
                       % (name, ", ".join("%.4f +- %.4f" % (x, s) for x, s in zip(c["ratio"], c["ratio_sigma"])),
                          ", ".join("%+.1f" % z for z in c["ratio_z"]), c["relmse_between"], c["relmse_noise"],
                          c["relmse_between"] / c["relmse_noise"], c["worst_block"]["ratio"], c["worst_block"]["z"],
                          verdict(c)))
        out.append("")
        if "mitsuba_long" in r:
            lg = r["mitsuba_long"]
            out.append("Against Mitsuba alone at %d spp (--mitsuba-long): fogrt / Mitsuba %s (z %s).\n"
                       % (lg["spp"], ", ".join("%.4f" % x for x in lg["ratio"]), ", ".join("%+.1f" % z for z in lg["z"])))
        if "near_light" in r:
            nl = r["near_light"]
            out.append("Near the light (the %d pixels 1 to 4 pixels from its image, against a 12x12-per-pixel quadrature): "
                       "fogrt %.4f (z %+.1f), Mitsuba %.4f (z %+.1f).\n"
                       % (nl["pixels"], nl["fogrt"]["ratio"], nl["fogrt"]["z"], nl["mitsuba"]["ratio"], nl["mitsuba"]["z"]))
        out.append("| renderer | spp | wall s | CPU s | relMSE (own noise) | relMSE at 10 CPU s | relMSE at 10 wall s |")
        out.append("| --- | --- | --- | --- | --- | --- | --- |")
        for key in ("fogrt", "mitsuba"):
            x = r[key]
            out.append("| %s | %d | %.1f | %.1f | %.3g | %.3g | %.3g |"
                       % ("fogrt" if key == "fogrt" else "Mitsuba", x["spp"], x["seconds"], x["cpu_seconds"],
                          x["relmse"], x["relmse_10cpus"], x["relmse_10s"]))
        out.append("| Mitsuba / fogrt (> 1: fogrt better) | | | | | %.2f | %.2f |"
                   % (r["mitsuba"]["relmse_10cpus"] / r["fogrt"]["relmse_10cpus"],
                      r["mitsuba"]["relmse_10s"] / r["fogrt"]["relmse_10s"]))
        out.append("")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    main()
