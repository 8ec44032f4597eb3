/* The --fixed paths of `qorient convert` and `qorient slerp`. */
#include "cli.h"

qo_status qo_cli_convert_fixed(const struct rep_spec *from, const struct rep_spec *to,
                               const double *v, int degrees, double *o, size_t *n)
{
    (void)from; (void)to; (void)v; (void)degrees; (void)o;
    *n = 0;
    return QO_E_ARG; /* TEMPORARY until the fixed core merges */
}

qo_status qo_cli_slerp_fixed(const double *v, double *o)
{
    (void)v; (void)o;
    return QO_E_ARG;
}
