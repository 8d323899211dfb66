/* cmocka's float comparison works in single precision; mimas' checks need
 * double.  Include after <cmocka.h>. */
#ifndef MIMAS_TEST_ASSERT_CLOSE_H
#define MIMAS_TEST_ASSERT_CLOSE_H

#include <math.h>

#define assert_close(a, b, tol)                                                        \
    do {                                                                               \
        double a_ = (a), b_ = (b), t_ = (tol);                                         \
        if (!(fabs(a_ - b_) <= t_))                                                    \
            fail_msg("%s = %.17g differs from %s = %.17g by %.3g (tolerance %.3g)", #a, \
                     a_, #b, b_, fabs(a_ - b_), t_);                                   \
    } while (0)

#endif
