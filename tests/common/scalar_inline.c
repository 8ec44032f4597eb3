/* The scalar inline bodies (see scalar_inline.h): QO_NO_SIMD before the first qorient header. */
#define QO_NO_SIMD
#include "common/scalar_inline.h"
#include "qorient/convert.h"
#include "qorient/quat.h"

qo_quat_f32 scalar_quat_mul_f32(qo_quat_f32 a, qo_quat_f32 b) { return qo_quat_mul_f32(a, b); }

qo_vec3_f32 scalar_quat_rotate_f32(qo_quat_f32 q, qo_vec3_f32 v)
{
    return qo_quat_rotate_f32(q, v);
}

qo_status scalar_quat_normalize_f32(qo_quat_f32 q, qo_quat_f32 *out)
{
    return qo_quat_normalize_f32(q, out);
}

qo_status scalar_quat_to_mat3_f32(qo_quat_f32 q, qo_mat3_f32 *out)
{
    return qo_mat3_from_quat_f32(q, out);
}
