// bench/compare/k_eigen.cpp - Eigen 3.4 (Debian libeigen3-dev, header-only) kernels of the
// comparison (see bench.h). Quaternionf stores x,y,z,w (16-byte aligned, SSE-vectorised
// product); matrices are Matrix3f (column-major). Eigen 3.4 has no quaternion -> Euler: the
// documented route is q.toRotationMatrix().eulerAngles(a0, a1, a2), intrinsic, any of the 12
// sequences (ranges [0,pi] x [-pi,pi] x [-pi,pi], which the accuracy check does not care
// about: it composes the angles back).
#include <Eigen/Geometry>
#include <vector>

#include "bench.h"

typedef std::vector<Eigen::Quaternionf, Eigen::aligned_allocator<Eigen::Quaternionf> > QuatVec;
static QuatVec g_qa(BK_N), g_qb(BK_N), g_qn(BK_N), g_q(BK_N);
static std::vector<Eigen::Vector3f> g_vin(BK_N), g_v(BK_N), g_e(BK_N);
static std::vector<Eigen::Matrix3f> g_min(BK_N), g_m(BK_N);
static std::vector<float> g_t(BK_N);

static Eigen::Quaternionf to_eigen(qo_quat_f32 q) { return Eigen::Quaternionf(q.w, q.x, q.y, q.z); }

extern "C" void bk_eigen_load(const bk_input *in)
{
    for (int i = 0; i < BK_N; i++) {
        g_qa[i] = to_eigen(in->qa[i]);
        g_qb[i] = to_eigen(in->qb[i]);
        g_qn[i] = to_eigen(in->qn[i]);
        g_vin[i] = Eigen::Vector3f(in->v[i].x, in->v[i].y, in->v[i].z);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) g_min[i](r, c) = in->m[i].m[r][c];
        g_t[i] = in->t[i];
    }
}

static void fetch(bk_output *o)
{
    for (int i = 0; i < BK_N; i++) {
        o->q[i].w = g_q[i].w(); o->q[i].x = g_q[i].x(); o->q[i].y = g_q[i].y(); o->q[i].z = g_q[i].z();
        o->v[i].x = g_v[i].x(); o->v[i].y = g_v[i].y(); o->v[i].z = g_v[i].z();
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) o->m[i].m[r][c] = g_m[i](r, c);
        o->e[i][0] = g_e[i][0]; o->e[i][1] = g_e[i][1]; o->e[i][2] = g_e[i][2];
    }
}

extern "C" void bk_eigen_mul(void)
{
    for (int i = 0; i < BK_N; i++) g_q[i] = g_qa[i] * g_qb[i];
}

extern "C" void bk_eigen_rotate(void)
{
    for (int i = 0; i < BK_N; i++) g_v[i] = g_qa[i] * g_vin[i];
}

extern "C" void bk_eigen_normalize(void)
{
    for (int i = 0; i < BK_N; i++) g_q[i] = g_qn[i].normalized();
}

extern "C" void bk_eigen_to_mat3(void)
{
    for (int i = 0; i < BK_N; i++) g_m[i] = g_qa[i].toRotationMatrix();
}

extern "C" void bk_eigen_from_mat3(void)
{
    for (int i = 0; i < BK_N; i++) g_q[i] = Eigen::Quaternionf(g_min[i]);
}

template <int A0, int A1, int A2> static void euler()
{
    for (int i = 0; i < BK_N; i++) g_e[i] = g_qa[i].toRotationMatrix().eulerAngles(A0, A1, A2);
}

extern "C" void bk_eigen_to_euler_XYZ(void) { euler<0, 1, 2>(); }
extern "C" void bk_eigen_to_euler_ZYX(void) { euler<2, 1, 0>(); }
extern "C" void bk_eigen_to_euler_ZXZ(void) { euler<2, 0, 2>(); }

extern "C" void bk_eigen_slerp(void)
{
    for (int i = 0; i < BK_N; i++) g_q[i] = g_qa[i].slerp(g_t[i], g_qb[i]);
}

extern "C" const bk_kernel bk_eigen_kernels[] = {
    { "eigen", "mul", bk_eigen_mul, fetch },
    { "eigen", "rotate", bk_eigen_rotate, fetch },
    { "eigen", "normalize", bk_eigen_normalize, fetch },
    { "eigen", "to_mat3", bk_eigen_to_mat3, fetch },
    { "eigen", "from_mat3", bk_eigen_from_mat3, fetch },
    { "eigen", "to_euler_XYZ", bk_eigen_to_euler_XYZ, fetch },
    { "eigen", "to_euler_ZYX", bk_eigen_to_euler_ZYX, fetch },
    { "eigen", "to_euler_ZXZ", bk_eigen_to_euler_ZXZ, fetch },
    { "eigen", "slerp", bk_eigen_slerp, fetch },
    { 0, 0, 0, 0 }
};
