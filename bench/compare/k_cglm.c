/* bench/compare/k_cglm.c - cglm (Debian libcglm-dev, header-only, inline) kernels of the
 * comparison (see bench.h). Inputs are held in cglm's own layout: versor = x,y,z,w (16-byte
 * aligned), mat3 column-major m[col][row]. cglm offers quaternion -> Euler only as
 * glm_euler_angles on a mat4 (one sequence: R = Rx Ry Rz, i.e. intrinsic XYZ), so that
 * kernel is glm_quat_mat4 + glm_euler_angles. glm_quat_rotatev normalises q on every call. */
#include <cglm/cglm.h>

#include "bench.h"

static versor g_qa[BK_N], g_qb[BK_N], g_qn[BK_N], g_q[BK_N];
static vec3 g_vin[BK_N], g_v[BK_N];
static mat3 g_min[BK_N], g_m[BK_N];
static vec3 g_e[BK_N];
static float g_t[BK_N];

static void to_versor(qo_quat_f32 q, versor out)
{
    glm_quat_init(out, q.x, q.y, q.z, q.w);
}

void bk_cglm_load(const bk_input *in)
{
    int i, r, c;
    for (i = 0; i < BK_N; i++) {
        to_versor(in->qa[i], g_qa[i]);
        to_versor(in->qb[i], g_qb[i]);
        to_versor(in->qn[i], g_qn[i]);
        g_vin[i][0] = in->v[i].x; g_vin[i][1] = in->v[i].y; g_vin[i][2] = in->v[i].z;
        for (r = 0; r < 3; r++)
            for (c = 0; c < 3; c++) g_min[i][c][r] = in->m[i].m[r][c];
        g_t[i] = in->t[i];
    }
}

static void fetch(bk_output *o)
{
    int i, r, c;
    for (i = 0; i < BK_N; i++) {
        o->q[i].w = g_q[i][3]; o->q[i].x = g_q[i][0]; o->q[i].y = g_q[i][1]; o->q[i].z = g_q[i][2];
        o->v[i].x = g_v[i][0]; o->v[i].y = g_v[i][1]; o->v[i].z = g_v[i][2];
        for (r = 0; r < 3; r++)
            for (c = 0; c < 3; c++) o->m[i].m[r][c] = g_m[i][c][r];
        o->e[i][0] = g_e[i][0]; o->e[i][1] = g_e[i][1]; o->e[i][2] = g_e[i][2];
    }
}

void bk_cglm_mul(void);
void bk_cglm_mul(void)
{
    int i;
    for (i = 0; i < BK_N; i++) glm_quat_mul(g_qa[i], g_qb[i], g_q[i]);
}

void bk_cglm_rotate(void);
void bk_cglm_rotate(void)
{
    int i;
    for (i = 0; i < BK_N; i++) glm_quat_rotatev(g_qa[i], g_vin[i], g_v[i]);
}

void bk_cglm_normalize(void);
void bk_cglm_normalize(void)
{
    int i;
    for (i = 0; i < BK_N; i++) glm_quat_normalize_to(g_qn[i], g_q[i]);
}

void bk_cglm_to_mat3(void);
void bk_cglm_to_mat3(void)
{
    int i;
    for (i = 0; i < BK_N; i++) glm_quat_mat3(g_qa[i], g_m[i]);
}

void bk_cglm_from_mat3(void);
void bk_cglm_from_mat3(void)
{
    int i;
    for (i = 0; i < BK_N; i++) glm_mat3_quat(g_min[i], g_q[i]);
}

void bk_cglm_to_euler_XYZ(void);
void bk_cglm_to_euler_XYZ(void)
{
    int i;
    for (i = 0; i < BK_N; i++) {
        mat4 m;
        glm_quat_mat4(g_qa[i], m);
        glm_euler_angles(m, g_e[i]);
    }
}

void bk_cglm_slerp(void);
void bk_cglm_slerp(void)
{
    int i;
    for (i = 0; i < BK_N; i++) glm_quat_slerp(g_qa[i], g_qb[i], g_t[i], g_q[i]);
}

const bk_kernel bk_cglm_kernels[] = {
    { "cglm", "mul", bk_cglm_mul, fetch },
    { "cglm", "rotate", bk_cglm_rotate, fetch },
    { "cglm", "normalize", bk_cglm_normalize, fetch },
    { "cglm", "to_mat3", bk_cglm_to_mat3, fetch },
    { "cglm", "from_mat3", bk_cglm_from_mat3, fetch },
    { "cglm", "to_euler_XYZ", bk_cglm_to_euler_XYZ, fetch },
    { "cglm", "slerp", bk_cglm_slerp, fetch },
    { 0, 0, 0, 0 }
};
