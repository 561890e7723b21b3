// Minimal drop-in use of wrinkle from C++17, two translation units: impl.cpp compiles the kit,
// this file only includes its declarations. Build (installed kit):
//     c++ -std=c++17 impl.cpp main.cpp $(pkg-config --cflags --libs wrinkle) -o minimal_cpp
// Same two jobs as examples/minimal_c: optimal resolution + meshed panel (Style3D), then a coarse
// sheet wrinkled by the TFW wrinkle field and upsampled.
#include "wrinkle/wrinkle.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace {

// RAII owners for the C structs (each wrinkle create/fill pairs with one free).
struct MesherResult {
    wr_mesher_result r;
    MesherResult() { std::memset(&r, 0, sizeof r); }
    ~MesherResult() { wr_mesher_free(&r); }
};
struct Mesh {
    wr_mesh m;
    Mesh() { std::memset(&m, 0, sizeof m); }
    ~Mesh() { wr_mesh_free(&m); }
};
struct Field {
    wr_wf wf;
    Field() { std::memset(&wf, 0, sizeof wf); }
    ~Field() { wr_wf_free(&wf); }
};

int fail(const char *what, const wr_diag &d) {
    std::fprintf(stderr, "%s: %s\n", what, d.message);
    return 1;
}

int mesh_a_panel() {
    const double B = 2.6e-6, E = 2.0e6; // Style3D Table 1 "Green" [N·m], [N/m²]
    std::vector<double> outline = {0, 0, 0.30, 0, 0.30, 0.20, 0, 0.20}; // 300 × 200 mm [m]
    wr_resolution_model model = wr_resolution_model_paper();
    wr_diag d;
    double r = 0.0;
    if (wr_resolution_from_BE(&model, B, E, nullptr, &r, &d) != WR_OK) return fail("resolution", d);
    wr_pattern_panel panel{};
    panel.name = "panel";
    panel.outer.xy = outline.data();
    panel.outer.n = 4;
    panel.fabric.B = B;
    panel.fabric.E = E;
    wr_pattern pattern{};
    pattern.panels = &panel;
    pattern.n_panels = 1;
    MesherResult res;
    if (wr_mesher_run(&pattern, nullptr, &res.r, &d) != WR_OK) return fail("mesher", d);
    std::printf("fabric B=%g N*m E=%g N/m^2: optimal resolution %.2f mm\n", B, E, 1e3 * r);
    std::printf("panel 300x200 mm: %d vertices, %d triangles, min angle %.1f deg, mean edge/sizing %.3f\n",
                (int)res.r.mesh.nv, (int)res.r.mesh.nf, res.r.report.min_angle_deg, res.r.report.ratio_mean);
    return 0;
}

int wrinkle_a_sheet() {
    const double L = 0.25, H = 0.10, PI = 3.14159265358979323846;
    wr_diag d;
    Mesh coarse;
    if (wr_mesh_rectangle(&coarse.m, L, H, 12, 5, &d) != WR_OK) return fail("mesh", d);
    const wr_mesh &m = coarse.m;
    // Base surface: 10% stretch along x, width pulled in by up to 10% mid-span (more than the
    // Poisson contraction), as a tension-field solve of a stretched strip would give.
    std::vector<double> base(3 * (size_t)m.nv);
    for (int32_t v = 0; v < m.nv; ++v) {
        double x = m.pos[3 * v], y = m.pos[3 * v + 1];
        base[3 * v] = 1.1 * x;
        base[3 * v + 1] = (y - 0.5 * H) * (1.0 - 0.1 * std::sin(PI * x / L)) + 0.5 * H;
        base[3 * v + 2] = 0.0;
    }
    wr_wf_material mat{};
    mat.young = 1e6;
    mat.poisson = 0.5;
    mat.thickness = 1e-4;
    Field field;
    if (wr_wf_create(&field.wf, &m, base.data(), &mat, &d) != WR_OK) return fail("wr_wf_create", d);
    std::vector<uint8_t> clamped((size_t)m.nf, 0); // clamped ends: the wrinkle-free set W (TFW Sec. 5.1)
    for (int32_t f = 0; f < m.nf; ++f) {
        double cx = 0.0;
        for (int k = 0; k < 3; ++k) cx += m.pos[3 * m.faces[3 * f + k]] / 3.0;
        clamped[f] = (uint8_t)(cx < 0.02 || cx > L - 0.02);
    }
    wr_wf_set_wrinkle_free(&field.wf, clamped.data());
    std::vector<double> a((size_t)m.nv), omega((size_t)m.ne), phi(3 * (size_t)m.nf);
    if (wr_wf_init(&field.wf, nullptr, a.data(), omega.data(), &d) != WR_OK) return fail("wr_wf_init", d);
    wr_wf_solve_desc sd{};
    sd.max_iter = 60;
    wr_wf_solve_stats ss{};
    wr_status st = wr_wf_solve(&field.wf, &sd, a.data(), omega.data(), &ss, &d);
    if (st != WR_OK && st != WR_ERR_NOT_CONVERGED) return fail("wr_wf_solve", d);
    if (wr_wf_phase(&field.wf, omega.data(), phi.data(), nullptr, &d) != WR_OK) return fail("wr_wf_phase", d);
    wr_wf_upsample_desc ud{};
    ud.levels = 3;
    Mesh fine;
    if (wr_wf_upsample(&field.wf, a.data(), phi.data(), &ud, &fine.m, nullptr, &d) != WR_OK)
        return fail("wr_wf_upsample", d);
    double amax = *std::max_element(a.begin(), a.end()), zmax = 0.0;
    for (int32_t v = 0; v < fine.m.nv; ++v) zmax = std::max(zmax, std::fabs(fine.m.pos[3 * v + 2]));
    std::printf("coarse sheet %d vertices: SQP %d iterations (%s), E_wf %.4g -> %.4g J, max amplitude %.3f mm\n",
                (int)m.nv, (int)ss.iterations, wr_status_string(st), ss.energy0, ss.energy, 1e3 * amax);
    std::printf("wrinkled surface: %d vertices, max |z| %.3f mm\n", (int)fine.m.nv, 1e3 * zmax);
    return 0;
}

} // namespace

int main() {
    int rc = mesh_a_panel();
    return rc ? rc : wrinkle_a_sheet();
}
