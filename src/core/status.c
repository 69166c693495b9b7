/* status.c - human-readable text for sol_status. */
#include "sol_core.h"

const char *sol_status_string(sol_status status)
{
    switch (status) {
    case SOL_OK: return "ok";
    case SOL_ERR_NULL_ARG: return "a required pointer is NULL";
    case SOL_ERR_INVALID_ARG: return "invalid argument";
    case SOL_ERR_NONFINITE: return "input contains NaN or infinity";
    case SOL_ERR_ZERO_LENGTH: return "zero-length vector";
    case SOL_ERR_OUT_OF_RANGE: return "value out of the format's range";
    case SOL_ERR_NO_MEMORY: return "out of memory";
    case SOL_ERR_IO: return "file input/output error";
    case SOL_ERR_FORMAT: return "malformed or unsupported file";
    case SOL_ERR_UNSUPPORTED: return "not supported by this build";
    case SOL_ERR_NO_CONVERGENCE: return "iteration did not converge";
    case SOL_ERR_SOLVER: return "solver failure";
    case SOL_ERR_LIMIT: return "input exceeds the size or work limit";
    case SOL_STATUS_COUNT: break;
    }
    return "unknown status";
}
