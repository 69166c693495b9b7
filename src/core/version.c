/* version.c - the library's version (SOL_VERSION_* in sol_core.h). */
#include "sol_core.h"

const char *sol_version(void)
{
    return SOL_VERSION_STRING;
}
