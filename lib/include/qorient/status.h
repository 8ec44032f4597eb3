/*
 * qorient/status.h - the status code every fallible qorient function returns.
 *
 * Index:
 *   qo_status            enum of all outcomes, QO_OK == 0
 *   qo_status_str()      short, stable, lower-case reason text for a status
 *
 * Conventions (whole library):
 *   - A function that can fail returns qo_status and writes its result through its last
 *     parameter(s). That output is ALWAYS written with a defined value, also on error
 *     (each function documents which value: usually identity / zero / the clamped input).
 *   - QO_OK is 0, every error is positive, so `if (st != QO_OK)` and `if (st)` both work.
 *   - The numeric values are part of the ABI: new codes are only ever appended.
 */
#ifndef QORIENT_STATUS_H
#define QORIENT_STATUS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum qo_status {
    QO_OK = 0,            /* success */
    QO_E_NULL,            /* a required pointer argument was NULL */
    QO_E_NONFINITE,       /* an input was NaN or +-Inf */
    QO_E_DEGENERATE,      /* zero-length quaternion, vector or axis where a direction is needed */
    QO_E_RANGE,           /* a parameter is outside its documented range (e.g. t not in [0,1]) */
    QO_E_NOT_ROTATION,    /* a matrix is not orthonormal with determinant +1 within tolerance */
    QO_E_TOO_FEW,         /* fewer keyframes / points / joints than the operation needs */
    QO_E_ORDER,           /* times or keys not strictly increasing */
    QO_E_LIMIT,           /* a limit (velocity, acceleration, jerk, rate) is zero, negative or non-finite */
    QO_E_OVERFLOW,        /* a fixed-point result saturated; the output holds the saturated value */
    QO_E_ARG,             /* an enum or option value is not one this function knows */
    QO_E_CAPACITY,        /* caller-provided storage is too small */
    QO_E_INFEASIBLE,      /* no motion satisfies the constraints (e.g. target outside joint limits) */
    QO_E_IO,              /* port: a bus or device operation failed */
    QO_E_TIMEOUT,         /* port: the peer did not answer in time */
    QO_E_DISCONNECTED,    /* port: the connection is down */
    QO_E_CONFIG,          /* port: a configuration (register map, device name) is invalid */
    QO_E_PROTOCOL,        /* port: the peer answered with an exception or malformed reply */
    QO_E_STATE,           /* an object was used before init or after it stopped */
    QO_STATUS_COUNT_      /* number of codes; not a status */
} qo_status;

/*
 * Returns a short, constant, lower-case reason for `st` ("ok", "zero-length quaternion or
 * vector", ...). Never NULL: an unknown value gives "unknown status". The text is what the
 * `qorient` command prints after "error: ".
 */
const char *qo_status_str(qo_status st);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_STATUS_H */
