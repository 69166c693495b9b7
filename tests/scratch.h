/* scratch.h - per-process scratch paths for tests that write files. */
#ifndef SOL_TESTS_SCRATCH_H
#define SOL_TESTS_SCRATCH_H

#include <stdio.h>
#include <unistd.h>

/* /tmp/sol_<pid>_<name>: Criterion runs each test in its own child, so two test runs at once
 * (make test beside make sanitize) never share a file. Four rotating buffers let one call use
 * several names. */
static inline const char *scratch(const char *name)
{
    static char buf[4][256];
    static int next;
    char *b = buf[next++ & 3];
    snprintf(b, sizeof buf[0], "/tmp/sol_%d_%s", (int)getpid(), name);
    return b;
}

#endif
