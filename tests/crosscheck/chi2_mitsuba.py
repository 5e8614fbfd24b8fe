#!/usr/bin/env python3
"""fogrt's direction samplers in Mitsuba 3's chi-square harness (mitsuba.chi2).

    python3 tests/crosscheck/chi2_mitsuba.py [--venv DIR] [--out DIR] [--cc CC]

Optional, never part of `make test` (`make chi2-mitsuba` runs it). fogrt's own chi-square
tests (tests/test_sampling.c, docs/distributions.md) bin each sampler on grids made for it;
this runs the same samplers through an outside harness, Mitsuba's ChiSquareTest on its
SphericalDomain, with Mitsuba's own sampler of the same density beside each one as the
control. Mitsuba's harness finds the expected count of a cell by integrating the pdf over
it with a few quadrature points per cell (ires, 4 by default): a density that peaks inside
one cell, as Henyey-Greenstein does at |g| = 0.99, is integrated wrongly there and the test
rejects any sampler, Mitsuba's own included; so does a density with a jump (the footprint
of a spot light ends at the rim of its lit patch), whose edge cells a few points per cell
integrate wrongly: Mitsuba's own uniform cone (square_to_uniform_cone, cos 0.5 or 0.2) is
rejected at ires 16 and 64 alike. So every case runs three times: with the harness's
defaults, with ires = 16 and with ires = 64. A case fails only when fogrt is rejected where
the control, under the same settings, is accepted (or, for a sampler Mitsuba does not
have, when fogrt is rejected at ires = 64), or when a negative control (HG sampled at
g = 0.6, its pdf given at 0.57; the footprint's pdf without its sphere's part; two HG lobes
whose pdf has the weights swapped) is accepted. Appendix G's two HG lobes run beside
Mitsuba's blendphase of two hg, its Rayleigh beside Mitsuba's rayleigh. The table goes to
OUT/results.md.

fogrt's samplers are compiled from fogrt.h into a shared library (chi2_shim.c) and called
through ctypes on whole batches. The harness needs Mitsuba's llvm_ad_rgb variant (Debian's
libllvm19; the script finds it as crosscheck.py does).
"""
import argparse
import ctypes
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import crosscheck  # noqa: E402  (the virtual environment and the LLVM search)

GENERIC_WO = (0.3, -0.5, 0.812)
# the samplers of chi2_shim.c, by its kind argument
HG, GLOW, COSINE, SPHERE, HG_WRONG_PDF, FOOTPRINT, FOOTPRINT_WRONG_PDF, HG2, RAYLEIGH, HG2_WRONG_PDF = range(10)
NEGATIVE = (HG_WRONG_PDF, FOOTPRINT_WRONG_PDF, HG2_WRONG_PDF)   # the negative controls: must be rejected
HG2_ROWS = ((0.8, -0.4, 0.7), (0.95, -0.7, 0.5), (-0.3, 0.6, 0.25))   # chi2_shim.c's HG2: g1, g2, w
IRES = (4, 16, 64)   # quadrature points per cell side: the harness's default, then finer


def unit(v):
    n = sum(x * x for x in v) ** 0.5
    return tuple(x / n for x in v)


def cases():
    """(name, kind, param, wo, mitsuba control or None)."""
    out = []
    for g in (0.0, 0.5, -0.5, 0.9, -0.9, 0.99, -0.99):
        out.append(("HG g = %+.2f, generic wo" % g, HG, g, unit(GENERIC_WO), ("hg", g)))
    for g in (0.99, -0.99):
        out.append(("HG g = %+.2f, wo on the grid's pole" % g, HG, g, (0.0, 0.0, 1.0), ("hg", g)))
    out.append(("glow around a lamp, generic direction", GLOW, 0.0, unit(GENERIC_WO), None))
    # the footprint of a spot on a floor (chi2_shim.c), seen from a fog point: outside the
    # sphere around the lit patch (both ways mixed) and inside it (the lamp's cone alone)
    out.append(("spot's footprint, from outside its sphere", FOOTPRINT, 0.0, (-1.2, 1.1, 1.0), None))
    out.append(("spot's footprint, from inside its sphere", FOOTPRINT, 0.0, (0.3, 0.5, 0.2), None))
    # appendix G: two HG lobes beside Mitsuba's blendphase of two hg, Rayleigh beside its rayleigh
    for row, (g1, g2, w) in enumerate(HG2_ROWS):
        out.append(("two lobes %g, %g, w = %g, generic wo" % (g1, g2, w), HG2, float(row), unit(GENERIC_WO),
                    ("blend", (g1, g2, w))))
    out.append(("Rayleigh, generic wo", RAYLEIGH, 0.0, unit(GENERIC_WO), ("rayleigh", 0.0)))
    out.append(("cosine hemisphere", COSINE, 0.0, (0.0, 0.0, 1.0), ("cosine", 0.0)))
    out.append(("uniform sphere", SPHERE, 0.0, (0.0, 0.0, 1.0), ("sphere", 0.0)))
    out.append(("negative control: HG g = 0.6, pdf at g = 0.57", HG_WRONG_PDF, 0.6, unit(GENERIC_WO), None))
    out.append(("negative control: the footprint, pdf of the lamp's cone alone", FOOTPRINT_WRONG_PDF, 0.0, (-1.2, 1.1, 1.0), None))
    out.append(("negative control: two lobes 0.8, -0.4, w = 0.7, pdf with w = 0.3", HG2_WRONG_PDF, 0.0, unit(GENERIC_WO), None))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--venv", default=os.path.join(ROOT, "build", "crosscheck-venv"))
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "chi2-mitsuba"))
    ap.add_argument("--cc", default=os.environ.get("CC", "cc"))
    args = ap.parse_args()
    crosscheck.ensure_environment(args.venv)
    variant, _ = crosscheck.choose_variant("llvm")

    args.out = os.path.abspath(args.out)
    os.makedirs(args.out, exist_ok=True)
    os.chdir(args.out)   # the harness writes chi2_data.py next to it on every rejection
    lib_path = os.path.join(args.out, "libchi2_shim.so")
    subprocess.check_call([args.cc, "-std=c99", "-O2", "-shared", "-fPIC", "-I" + ROOT, "-o", lib_path,
                           os.path.join(HERE, "chi2_shim.c"), "-lm"])
    lib = ctypes.CDLL(lib_path)

    import numpy as np
    import mitsuba as mi
    mi.set_variant(variant)
    import drjit as dr
    from mitsuba.chi2 import ChiSquareTest, SphericalDomain, PhaseFunctionAdapter

    fp = ctypes.POINTER(ctypes.c_float)

    def ptr(a):
        return a.ctypes.data_as(fp)

    def fogrt_funcs(kind, param, wo):
        c = [ctypes.c_int(kind), ctypes.c_float(param)] + [ctypes.c_float(x) for x in wo]

        def sample(s):
            u1 = np.ascontiguousarray(np.array(s.x, dtype=np.float32))
            u2 = np.ascontiguousarray(np.array(s.y, dtype=np.float32))
            n = len(u1)
            w = np.zeros(3 * n, dtype=np.float32)
            lib.chi2_sample(*c, ptr(u1), ptr(u2), ptr(w), ctypes.c_int(n))
            w = w.reshape(n, 3)
            return mi.Vector3f(w[:, 0], w[:, 1], w[:, 2])

        def pdf(v):
            w = np.ascontiguousarray(np.stack([np.array(v.x), np.array(v.y), np.array(v.z)], 1)
                                     .astype(np.float32).ravel())
            n = len(w) // 3
            p = np.zeros(n, dtype=np.float32)
            lib.chi2_pdf(*c, ptr(w), ptr(p), ctypes.c_int(n))
            return mi.Float(p)
        return sample, pdf, 2

    def mitsuba_funcs(control, wo):
        kind, g = control
        if kind == "hg":
            s, p = PhaseFunctionAdapter("hg", "<float name='g' value='%r'/>" % g, wi=list(wo))
            return s, p, 3
        if kind == "blend":   # Mitsuba's weight is the second phase's: fogrt's w HG(g1) + (1 - w) HG(g2)
            g1, g2, w = g
            inner = ("<float name='weight' value='%r'/><phase type='hg'><float name='g' value='%r'/></phase>"
                     "<phase type='hg'><float name='g' value='%r'/></phase>" % (1.0 - w, g1, g2))
            s, p = PhaseFunctionAdapter("blendphase", inner, wi=list(wo))
            return s, p, 3
        if kind == "rayleigh":
            s, p = PhaseFunctionAdapter("rayleigh", "", wi=list(wo))
            return s, p, 3
        if kind == "cosine":   # Mitsuba's pdf is cos / pi on the whole sphere: 0 below, as fogrt's
            return (mi.warp.square_to_cosine_hemisphere,
                    lambda v: dr.select(v.z > 0, mi.warp.square_to_cosine_hemisphere_pdf(v), 0.0), 2)
        return (mi.warp.square_to_uniform_sphere, mi.warp.square_to_uniform_sphere_pdf, 2)

    def run(funcs, ires):
        s, p, dim = funcs
        t = ChiSquareTest(domain=SphericalDomain(), sample_func=s, pdf_func=p, sample_dim=dim, ires=ires)
        ok = bool(t.run())
        pval = getattr(t, "p_value", None)
        msg = t.messages.strip().splitlines()
        why = next((m for m in msg if m.startswith("Failure")), "")
        return ok, pval, why

    def cell(r):
        ok, pval, why = r
        text = "accepted" if ok else "rejected"
        if pval is not None and why == "":
            text += " (p %.3g)" % float(pval)
        elif why:
            text += " (" + why.replace("Failure: ", "").rstrip(".") + ")"
        return text

    rows, bad = [], []
    for name, kind, param, wo, control in cases():
        line = [name]
        for ires in IRES:
            f = run(fogrt_funcs(kind, param, wo), ires)
            m = run(mitsuba_funcs(control, wo), ires) if control else None
            line += [cell(f), cell(m) if m else "-"]
            if kind in NEGATIVE:
                if f[0]:
                    bad.append("%s accepted at ires %d (the harness cannot tell a wrong pdf)" % (name, ires))
            elif not f[0] and (m[0] if m else ires == IRES[-1]):
                bad.append("%s, ires %d" % (name, ires))
            print("chi2-mitsuba: %-40s ires %2d  fogrt %-9s  Mitsuba %s" %
                  (name, ires, "accepted" if f[0] else "REJECTED",
                   ("accepted" if m[0] else "rejected") if m else "-"), flush=True)
        rows.append(line)

    with open(os.path.join(args.out, "results.md"), "w") as md:
        md.write("Mitsuba 3's chi-square harness (%s, SphericalDomain, res 101, 10^6 samples, "
                 "significance 0.01) on fogrt's samplers, Mitsuba's own beside them.\n\n" % variant)
        md.write("| sampler |" + "".join(" fogrt, ires %d | Mitsuba, ires %d |" % (r, r) for r in IRES) + "\n")
        md.write("| --- |" + " --- | --- |" * len(IRES) + "\n")
        for line in rows:
            md.write("| " + " | ".join(line) + " |\n")
    print("chi2-mitsuba: wrote %s" % os.path.join(args.out, "results.md"))
    if bad:
        print("chi2-mitsuba: FAILED: " + "; ".join(bad))
        return 1
    print("chi2-mitsuba: every fogrt sampler accepted wherever Mitsuba's own is; the negative controls rejected")
    return 0


if __name__ == "__main__":
    sys.exit(main())
