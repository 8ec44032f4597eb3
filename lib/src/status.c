#include "qorient/status.h"

const char *qo_status_str(qo_status st)
{
    /* A switch rather than a table indexed by st: an out-of-range value (a cast int from a
     * user's code) must not read past an array. */
    switch (st) {
    case QO_OK: return "ok";
    case QO_E_NULL: return "null pointer argument";
    case QO_E_NONFINITE: return "non-finite input (NaN or Inf)";
    case QO_E_DEGENERATE: return "zero-length quaternion or vector";
    case QO_E_RANGE: return "parameter out of range";
    case QO_E_NOT_ROTATION: return "matrix is not a rotation";
    case QO_E_TOO_FEW: return "too few keyframes or points";
    case QO_E_ORDER: return "times not strictly increasing";
    case QO_E_LIMIT: return "limit is zero, negative or non-finite";
    case QO_E_OVERFLOW: return "fixed-point overflow (saturated)";
    case QO_E_ARG: return "invalid argument";
    case QO_E_CAPACITY: return "storage too small";
    case QO_E_INFEASIBLE: return "constraints cannot be met";
    case QO_E_IO: return "bus or device i/o error";
    case QO_E_TIMEOUT: return "timeout";
    case QO_E_DISCONNECTED: return "disconnected";
    case QO_E_CONFIG: return "invalid configuration";
    case QO_E_PROTOCOL: return "protocol error or exception reply";
    case QO_E_STATE: return "object not initialised or stopped";
    case QO_STATUS_COUNT_: break;
    }
    return "unknown status";
}
