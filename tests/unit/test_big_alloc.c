/* Large zeroed arrays (src/big_alloc.c): zero, aligned (64 bytes; 2 MB from 2 MB up), freed
 * whichever way they were made, NULL on overflow, and the large ones advised for huge pages
 * (the kernel's flag on the mapping, read back from /proc/self/smaps). */
#include <config.h>

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "big_alloc.h"

#define MB (1u << 20)

static int all_zero(const unsigned char *p, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (p[k])
            return 0;
    return 1;
}

static void test_zero_and_aligned(void **state)
{
    (void)state;
    const size_t sizes[] = {0, 1, 100, 4096, 2 * MB - 8, 2 * MB, 2 * MB + 8, 7 * MB + 123};
    for (int round = 0; round < 2; round++)
        for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
            size_t n = sizes[k];
            unsigned char *p = mimas_big_calloc(n, 1);
            assert_non_null(p);
            assert_int_equal((uintptr_t)p % 64, 0);
            if (n >= 2 * MB)
                assert_int_equal((uintptr_t)p % (2 * MB), 0);
            assert_true(all_zero(p, n));
            memset(p, 0xa5, n); /* every byte is the array's: no header overwritten */
            mimas_big_free(p);
        }
    /* elements of any size; after memory with other contents was freed, zero again */
    double *d = mimas_big_calloc(300000, sizeof *d);
    assert_non_null(d);
    for (size_t k = 0; k < 300000; k++)
        assert_true(d[k] == 0.0);
    mimas_big_free(d);
    mimas_big_free(NULL);
}

static void test_overflow(void **state)
{
    (void)state;
    assert_null(mimas_big_calloc(SIZE_MAX / 2, 4));
    assert_null(mimas_big_calloc(4, SIZE_MAX / 2));
    assert_null(mimas_big_calloc(SIZE_MAX, 1));
    assert_null(mimas_big_calloc(SIZE_MAX - 10, 1));
}

/* the VmFlags of the mapping that holds p ("" if none) */
static void vm_flags_of(const void *p, char *flags, size_t cap)
{
    flags[0] = 0;
    FILE *fp = fopen("/proc/self/smaps", "r");
    if (!fp)
        return;
    char line[512];
    int inside = 0;
    while (fgets(line, sizeof line, fp)) {
        unsigned long lo, hi;
        if (sscanf(line, "%lx-%lx ", &lo, &hi) == 2 && strchr(line, '-') &&
            strchr(line, '-') < strchr(line, ' '))
            inside = (uintptr_t)p >= lo && (uintptr_t)p < hi;
        else if (inside && !strncmp(line, "VmFlags:", 8)) {
            snprintf(flags, cap, "%s", line + 8);
            break;
        }
    }
    fclose(fp);
}

static void test_huge_page_advice(void **state)
{
    (void)state;
    /* the flag where the kernel has transparent huge pages; under AddressSanitizer the
     * arrays are heap blocks, which it guards, and have none */
    int advised = 1;
#if defined(__SANITIZE_ADDRESS__)
    advised = 0;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
    advised = 0;
#endif
#endif
    FILE *fp = fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
    if (fp)
        fclose(fp);
    else
        advised = 0; /* a kernel without them refuses the advice */
    unsigned char *big = mimas_big_calloc(6 * MB, 1), *small = mimas_big_calloc(MB, 1);
    assert_non_null(big);
    assert_non_null(small);
    char flags[512];
    vm_flags_of(big, flags, sizeof flags);
    if (advised)
        assert_non_null(strstr(flags, " hg")); /* MADV_HUGEPAGE */
    else
        assert_null(strstr(flags, " hg"));
    vm_flags_of(small, flags, sizeof flags);
    assert_null(strstr(flags, " hg"));
    mimas_big_free(big);
    mimas_big_free(small);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_zero_and_aligned),
        cmocka_unit_test(test_overflow),
        cmocka_unit_test(test_huge_page_advice),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
