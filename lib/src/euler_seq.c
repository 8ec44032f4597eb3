/* The 24 Euler conventions: parsing, names, and the axis table both cores decompose with.
 * No float and no fixed point, so either core links it alone (see qorient/euler_seq.h). */
#include "qorient/euler_seq.h"

#include <stddef.h>

#include "euler_seq_internal.h"

const unsigned char qo_euler_seq_axes[12][3] = {
    {0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0},
    {0, 1, 0}, {0, 2, 0}, {1, 0, 1}, {1, 2, 1}, {2, 0, 2}, {2, 1, 2},
};

static const char *const seq_names[QO_EULER_SEQ_COUNT_] = {
    "xyz", "xzy", "yxz", "yzx", "zxy", "zyx", "xyx", "xzx", "yxy", "yzy", "zxz", "zyz",
    "XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ",
};

int qo_euler_seq_valid(qo_euler_seq seq)
{
    /* unsigned compare: also right where enums are unsigned chars (-fshort-enums on ARM EABI) */
    return (unsigned)seq < (unsigned)QO_EULER_SEQ_COUNT_;
}

qo_status qo_euler_seq_parse(const char *s, qo_euler_seq *out)
{
    int ax[3], i, upper = 0;
    if (out == NULL) return QO_E_NULL;
    *out = QO_EULER_SEQ_COUNT_;
    if (s == NULL) return QO_E_NULL;
    for (i = 0; i < 3; i++) {
        char c = s[i];
        int up;
        if (c >= 'x' && c <= 'z') { ax[i] = c - 'x'; up = 0; }
        else if (c >= 'X' && c <= 'Z') { ax[i] = c - 'X'; up = 1; }
        else return QO_E_ARG; /* also stops at the terminator of a short string */
        if (i == 0) upper = up;
        else if (up != upper) return QO_E_ARG;
    }
    if (s[3] != '\0') return QO_E_ARG;
    for (i = 0; i < 12; i++) {
        if (qo_euler_seq_axes[i][0] == ax[0] && qo_euler_seq_axes[i][1] == ax[1] && qo_euler_seq_axes[i][2] == ax[2]) {
            *out = (qo_euler_seq)(i + (upper ? 12 : 0));
            return QO_OK;
        }
    }
    return QO_E_ARG; /* two consecutive equal axes */
}

const char *qo_euler_seq_name(qo_euler_seq seq)
{
    return qo_euler_seq_valid(seq) ? seq_names[seq] : "invalid";
}

int qo_euler_seq_is_intrinsic(qo_euler_seq seq)
{
    return qo_euler_seq_valid(seq) && (int)seq >= 12;
}

int qo_euler_seq_is_proper(qo_euler_seq seq)
{
    return qo_euler_seq_valid(seq) && ((int)seq % 12) >= 6;
}
