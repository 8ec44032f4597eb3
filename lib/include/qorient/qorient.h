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
 *   gimbal.h    orientation paths and gimbal joint angles (hold band, rate limits), float32
 *   spline.h    multi-joint trajectories through keyframes, float32 planning and sampling
 *   motion.h    velocity/acceleration/jerk-limited multi-joint moves, re-planned online
 *   traj.h      one trajectory over N joints: keyframes or a queue of timed targets
 *   sink.h      the sink interface ports implement (N joint targets per tick)
 *   fmath.h     float32 kernels (sin, cos, atan2, asin, acos, exp, log) with stated error bounds
 *   fxmath.h    fixed-point primitives (mul, div, sqrt, sincos, atan2, asin, acos)
 *   fxconv.h    float <-> fixed boundary conversions (static inline; FPU-less code need not use)
 *   quat_fx.h, convert_fx.h, euler_fx.h   quaternion algebra, conversions, Euler: Q1.30 / Q3.28
 *   interp_fx.h lerp, nlerp, slerp, Bezier, Shoemake spline, squad segment, fixed point Q1.30
 *   spline_fx.h, motion_fx.h              fixed-point (Q16.16) per-tick samplers
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
#include "qorient/gimbal.h"
#include "qorient/spline.h"
#include "qorient/motion.h"
#include "qorient/traj.h"
#include "qorient/sink.h"
#include "qorient/fmath.h"
#include "qorient/fxmath.h"
#include "qorient/fxconv.h"
#include "qorient/quat_fx.h"
#include "qorient/convert_fx.h"
#include "qorient/euler_fx.h"
#include "qorient/interp_fx.h"
#include "qorient/spline_fx.h"
#include "qorient/motion_fx.h"

#endif /* QORIENT_QORIENT_H */
