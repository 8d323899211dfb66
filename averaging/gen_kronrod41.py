#!/usr/bin/env python3
"""Prints averaging/kronrod41.h: the abscissae and weights of the 41-point Gauss-Kronrod
rule on [-1, 1] and the weights of its embedded 20-point Gauss rule, read from GSL
(libgsl, whose tables are QUADPACK's): the abscissae as gsl_integration_qk41 evaluates
the integrand, the Kronrod weights from its result for integrands that are 1 at one
abscissa pair and 0 elsewhere, the Gauss weights from gsl_integration_glfixed_table_alloc(20)."""
import ctypes, ctypes.util

gsl = ctypes.CDLL(ctypes.util.find_library("gsl") or "libgsl.so")
FN = ctypes.CFUNCTYPE(ctypes.c_double, ctypes.c_double, ctypes.c_void_p)


class GslFunction(ctypes.Structure):
    _fields_ = [("function", FN), ("params", ctypes.c_void_p)]


class GlTable(ctypes.Structure):
    _fields_ = [("n", ctypes.c_size_t), ("x", ctypes.POINTER(ctypes.c_double)),
                ("w", ctypes.POINTER(ctypes.c_double)), ("precomputed", ctypes.c_int)]


D = ctypes.c_double
gsl.gsl_integration_qk41.argtypes = [ctypes.POINTER(GslFunction), D, D] + [ctypes.POINTER(D)] * 4
gsl.gsl_integration_glfixed_table_alloc.restype = ctypes.POINTER(GlTable)


def qk41(f):
    fn = GslFunction(FN(lambda x, p: f(x)), None)
    out = [D() for _ in range(4)]
    gsl.gsl_integration_qk41(ctypes.byref(fn), -1.0, 1.0, *[ctypes.byref(o) for o in out])
    return out[0].value


xs = []
qk41(lambda x: xs.append(x) or 0.0)
pos = sorted({abs(x) for x in xs}, reverse=True)  # 20 positive abscissae and 0
assert len(xs) == 41 and len(pos) == 21 and pos[-1] == 0.0
wgk = [qk41(lambda x, a=a: 1.0 if abs(x) == a else 0.0) / (1 if a == 0 else 2) for a in pos]
t = gsl.gsl_integration_glfixed_table_alloc(20).contents
gauss = {t.x[i]: t.w[i] for i in range(10)}
wg = []
for i, a in enumerate(pos[:20]):
    if i % 2 == 1:  # every other Kronrod abscissa is one of Gauss's
        g = min(gauss, key=lambda x: abs(x - a))
        assert abs(g - a) < 1e-15
        wg.append(gauss[g])
assert len(wg) == 10


def row(v):
    return ",\n".join("    %.17g" % x for x in v)


print("""/* The 41-point Gauss-Kronrod rule on [-1, 1] (Kronrod 1965; the tables of QUADPACK,
 * Piessens et al. 1983), as GSL's gsl_integration_qk41 holds it, printed to 17 digits by
 * gen_kronrod41.py: GK41_X[j] the abscissae (the rule takes +-GK41_X[j], and 0 once),
 * largest first, every other one (j odd) also an abscissa of the embedded 20-point Gauss
 * rule; GK41_WK their Kronrod weights (the last for 0); GK41_WG the Gauss weights of the
 * abscissae j = 1, 3, ..., 19. */
#ifndef MIMAS_KRONROD41_H
#define MIMAS_KRONROD41_H

static const double GK41_X[21] = {
%s};

static const double GK41_WK[21] = {
%s};

static const double GK41_WG[10] = {
%s};

#endif""" % (row(pos), row(wgk), row(wg)))
