/* fuzz_csv.c - libFuzzer target for sol_check_table_parse (the CSV reader of `sol check`,
 * src/check/table.c). */
#include <stdint.h>
#include <stdlib.h>

#include "sol_check.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    sol_read_limits limits = {.max_pixels = 1u << 20, .max_bytes = 1u << 24};
    sol_check_table t;
    size_t line = 0;
    if (sol_check_table_parse((const char *)data, size, &limits, &t, &line) == SOL_OK) {
        volatile double sum = 0;
        for (size_t i = 0; i < t.rows * t.cols; ++i)
            sum += t.values[i];
        (void)sum; /* clang: set but not used; volatile keeps the reads */
        sol_check_table_free(&t);
    }
    return 0;
}
