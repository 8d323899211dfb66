/* Gauss-Legendre rules on [-1, 1] (internal to the averaging module): for an
 * n-point rule, the n/2 positive nodes in increasing order and their weights; each node
 * x stands for the pair +-x.  Computed with 40-digit arithmetic (mpmath), rounded. */
#ifndef MIMAS_GAUSS_LEGENDRE_H
#define MIMAS_GAUSS_LEGENDRE_H

static const double gl4_x[2] = {0.33998104358485626, 0.86113631159405258};
static const double gl4_w[2] = {0.65214515486254614, 0.34785484513745386};
static const double gl6_x[3] = {0.23861918608319691, 0.66120938646626451, 0.93246951420315203};
static const double gl6_w[3] = {0.46791393457269105, 0.36076157304813861, 0.17132449237917035};
static const double gl8_x[4] = {0.1834346424956498, 0.52553240991632899, 0.79666647741362674, 0.96028985649753623};
static const double gl8_w[4] = {0.36268378337836198, 0.31370664587788729, 0.22238103445337447, 0.10122853629037626};
static const double gl10_x[5] = {0.14887433898163121, 0.43339539412924719, 0.67940956829902441, 0.86506336668898451, 0.97390652851717172};
static const double gl10_w[5] = {0.29552422471475287, 0.26926671930999636, 0.21908636251598204, 0.14945134915058059, 0.066671344308688138};
static const double gl12_x[6] = {0.12523340851146892, 0.36783149899818019, 0.58731795428661745, 0.76990267419430469, 0.90411725637047486, 0.98156063424671925};
static const double gl12_w[6] = {0.24914704581340279, 0.23349253653835481, 0.20316742672306592, 0.16007832854334623, 0.10693932599531843, 0.047175336386511827};
static const double gl16_x[8] = {0.09501250983763744, 0.28160355077925891, 0.45801677765722739, 0.61787624440264375, 0.75540440835500303, 0.86563120238783174, 0.94457502307323258, 0.98940093499164993};
static const double gl16_w[8] = {0.1894506104550685, 0.18260341504492359, 0.16915651939500254, 0.14959598881657673, 0.12462897125553387, 0.095158511682492785, 0.062253523938647893, 0.027152459411754095};

/* int_lo^hi f(x) dx ~ sum over the rule: the node and weight of pair member k of an
 * n-point rule (k < n; k < n/2 the negative nodes). */
static inline void gl_node(const double *xs, const double *ws, int n, int k, double lo,
                           double hi, double *x, double *wgt)
{
    int half = n / 2, m = k < half ? k : k - half;
    double mid = 0.5 * (lo + hi), rad = 0.5 * (hi - lo);
    *x = mid + (k < half ? -rad : rad) * xs[m];
    *wgt = rad * ws[m];
}

#endif

