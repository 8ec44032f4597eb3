/*
 * qorient/qorient.h - umbrella header: includes every public header of the portable core.
 * Prefer the module headers in firmware that wants to keep its include graph small.
 *
 *   status.h    qo_status and its text
 *   types.h     quaternion / vector / matrix value types, float32 and fixed point; conventions
 *   version.h   library version
 *   quat.h      quaternion algebra, float32
 *   convert.h   axis-angle, rotation vector, 3x3 matrix <-> quaternion, float32
 *   euler.h     Euler angles, 12 sequences x intrinsic/extrinsic, gimbal-lock report, float32
 *   interp.h    lerp, nlerp, slerp, Bezier, Shoemake spline, squad, float32
 *   fxmath.h    fixed-point primitives (mul, div, sqrt, sincos, atan2, asin, acos)
 *   interp_fx.h lerp, nlerp, slerp, Bezier, Shoemake spline, squad segment, fixed point Q1.30
 *   fxconv.h    float <-> fixed boundary conversions (static inline; FPU-less code need not use)
 */
#ifndef QORIENT_QORIENT_H
#define QORIENT_QORIENT_H

#include "qorient/status.h"
#include "qorient/types.h"
#include "qorient/version.h"
#include "qorient/quat.h"
#include "qorient/convert.h"
#include "qorient/euler.h"
#include "qorient/interp.h"
#include "qorient/fxmath.h"
#include "qorient/interp_fx.h"
#include "qorient/fxconv.h"

#endif /* QORIENT_QORIENT_H */
