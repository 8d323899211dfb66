/* Runs a fuzz target over saved inputs (the corpus), without libFuzzer:
 *   replay FILE...   (prints "ok N - FILE" lines, TAP) */
#include <config.h>

#include <stdio.h>
#include <stdlib.h>

#include "fuzz_input.h"

int main(int argc, char **argv)
{
    printf("1..%d\n", argc - 1);
    for (int k = 1; k < argc; k++) {
        FILE *fp = fopen(argv[k], "rb");
        if (!fp) {
            printf("not ok %d - %s (cannot open)\n", k, argv[k]);
            continue;
        }
        static uint8_t buf[1 << 20];
        size_t n = fread(buf, 1, sizeof buf, fp);
        fclose(fp);
        LLVMFuzzerTestOneInput(buf, n);
        printf("ok %d - %s\n", k, argv[k]);
    }
    return 0;
}
