#include "panels.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "hemirad/error.h"
#include "hemirad/image.h"
#include "hemirad/photometry.h"

namespace hemirad::view {

namespace {

double now_seconds() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

/// A luminance [W unit^-2] as the panels show it: lux (scene in metres) or W/unit^2.
double shown(const dvec3& E, bool lux) {
    const double y = luminance(E.r, E.g, E.b);
    return lux ? kLumensPerWatt * y : y;
}

} // namespace

Panels::Panels(GLFWwindow* window, const Scene& scene) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr; // no imgui.ini in the working directory
    ImGui::StyleColorsDark();
    ImGui::GetStyle().Alpha = 0.92f;
    if (!ImGui_ImplGlfw_InitForOpenGL(window, true) || !ImGui_ImplOpenGL3_Init("#version 410")) {
        ImGui::DestroyContext();
        throw RuntimeError("Dear ImGui: cannot initialise its GLFW or OpenGL 3 backend");
    }
    for (const hemirad::Luminaire& l : scene.luminaires)
        luminaires_.push_back(
            {l.name, l.multiplier > 0 ? l.multiplier : 1.0, l.multiplier > 0, 1.0f, l.multiplier});
    groups_.resize(scene.groups.size());
    for (std::size_t g = 0; g < scene.groups.size(); ++g) groups_[g].name = scene.groups[g];
    std::vector<bool> seen(scene.groups.size(), false);
    for (std::size_t p = 0; p < scene.polygons.size(); ++p) {
        const Polygon& poly = scene.polygons[p];
        Group& g = groups_[poly.group];
        if (scene.texture_of(std::uint32_t(p))) g.textured = true;
        if (seen[poly.group]) continue;
        seen[poly.group] = true;
        g.first_polygon = std::uint32_t(p);
        g.applied = scene.material_of(poly).rho;
        for (int c = 0; c < 3; ++c) g.rho[c] = float(g.applied[c]);
    }
}

void Panels::sync(const Scene& scene) {
    for (std::size_t k = 0; k < luminaires_.size() && k < scene.luminaires.size(); ++k) {
        Luminaire& l = luminaires_[k];
        const double m = scene.luminaires[k].multiplier;
        if (m == l.applied) continue;
        l.applied = m;
        l.on = m > 0;
        if (m > 0) l.dimmer = float(std::min(m / l.base, 1.0));
    }
    for (std::size_t k = 0; k < luminaires_.size() && k < scene.luminaires.size(); ++k) {
        Luminaire& l = luminaires_[k];
        const hemirad::Luminaire& s = scene.luminaires[k];
        if (s.position == l.placed && s.aim == l.aimed) continue;
        l.placed = s.position;
        l.aimed = s.aim;
        for (int c = 0; c < 3; ++c)
            l.position[c] = float(s.position[c]), l.aim[c] = float(s.aim[c]);
    }
    for (Group& g : groups_) {
        if (scene.polygons.empty()) break;
        const dvec3 rho = scene.material_of(scene.polygons[g.first_polygon]).rho;
        if (rho == g.applied) continue;
        g.applied = rho;
        for (int c = 0; c < 3; ++c) g.rho[c] = float(rho[c]);
    }
}

Panels::~Panels() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

bool Panels::wants_mouse() {
    return ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse;
}

bool Panels::wants_keyboard() {
    return ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard;
}

bool Panels::draw(Solver& solver, const PanelView& view, const PanelStats& stats) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    sync(solver.scene());
    bool edited = false;
    const auto apply = [&](auto&& edit) {
        try {
            edit();
            error_.clear();
            edited = true;
        } catch (const InputError& e) {
            error_ = e.what();
        }
    };
    const char* unit = stats.lux ? "lx" : "W/u2";
    const ImGuiWindowFlags flags = ImGuiWindowFlags_AlwaysAutoResize;

    // Solver and view, top left.
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Once);
    ImGui::Begin("Solver", nullptr, flags);
    const double bound = solver.error_bound(), tol = solver.options().tolerance;
    ImGui::Text("shots %ld   %.1f shots/s", solver.shots(), stats.shots_per_second);
    ImGui::Text("error bound %.3e (tolerance %.3g)", bound, tol);
    // Progress on a log scale: from a bound of 1 down to the tolerance.
    const double progress =
        bound <= tol ? 1.0 : std::clamp(std::log(bound) / std::log(std::max(tol, 1e-12)), 0.0, 1.0);
    ImGui::ProgressBar(float(progress), ImVec2(260, 0),
                       bound <= tol ? "converged" : (*view.paused ? "paused" : "solving"));
    ImGui::Text("unshot %.3e   frame %.1f ms", solver.unshot_fraction(), stats.frame_ms);
    ImGui::Checkbox("paused", view.paused);
    ImGui::Separator();
    float exposure = float(*view.exposure);
    if (ImGui::SliderFloat("exposure", &exposure, -8.0f, 8.0f, "%+.1f stops"))
        *view.exposure = exposure;
    ImGui::Checkbox("false colour", view.false_colour);
    ImGui::SameLine();
    ImGui::Checkbox("ambient term", view.ambient);
    if (!error_.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", error_.c_str());
    ImGui::End();

    // Luminaires: on/off and a dimmer (a fraction of the scene's multiplier), applied when the
    // slider is released.
    if (!luminaires_.empty()) {
        ImGui::SetNextWindowPos(ImVec2(8, 200), ImGuiCond_Once);
        ImGui::Begin("Luminaires", nullptr, flags);
        for (Luminaire& l : luminaires_) {
            ImGui::PushID(l.name.c_str());
            bool changed = ImGui::Checkbox("##on", &l.on);
            ImGui::SameLine();
            ImGui::SetNextItemWidth(160);
            ImGui::SliderFloat(l.name.c_str(), &l.dimmer, 0.0f, 1.0f, "%.2f");
            changed |= ImGui::IsItemDeactivatedAfterEdit();
            if (changed) {
                const double m = l.on ? l.base * double(l.dimmer) : 0.0;
                apply([&] { solver.set_luminaire_multiplier(l.name, m); });
                l.applied = std::nan(""); // the next frame shows what the scene holds
            }
            // Position and aim (scene units), applied when the field is left after an edit:
            // the luminaire's light leaves its old place and is shot from the new one.
            if (solver.has_light_layers() && ImGui::TreeNode("placement")) {
                ImGui::SetNextItemWidth(200);
                ImGui::DragFloat3("position", l.position, 0.05f, 0, 0, "%.2f");
                bool moved = ImGui::IsItemDeactivatedAfterEdit();
                ImGui::SetNextItemWidth(200);
                ImGui::DragFloat3("aim", l.aim, 0.02f, -1, 1, "%.2f");
                moved |= ImGui::IsItemDeactivatedAfterEdit();
                if (moved) {
                    apply([&] {
                        solver.place_luminaire(l.name,
                                               dvec3(l.position[0], l.position[1], l.position[2]),
                                               dvec3(l.aim[0], l.aim[1], l.aim[2]));
                    });
                    l.placed = dvec3(std::nan("")); // the next frame shows what the scene holds
                }
                ImGui::TreePop();
            }
            ImGui::PopID();
        }
        ImGui::End();
    }

    // Surface groups: reflectance (applied when the editor is released) and the leaf-level
    // irradiance statistics, refreshed four times a second.
    const double t = now_seconds();
    if (t - stats_time_ > 0.25) {
        stats_time_ = t;
        const Hierarchy& h = solver.hierarchy();
        for (std::size_t g = 0; g < groups_.size(); ++g)
            groups_[g].stats = group_irradiance(h, std::uint32_t(g));
    }
    ImGui::SetNextWindowPos(ImVec2(float(ImGui::GetIO().DisplaySize.x) - 8, 8), ImGuiCond_Once,
                            ImVec2(1, 0));
    ImGui::Begin("Surface groups", nullptr, flags);
    if (ImGui::BeginTable("groups", 5, ImGuiTableFlags_SizingFixedFit)) {
        ImGui::TableSetupColumn("group");
        ImGui::TableSetupColumn("reflectance");
        ImGui::TableSetupColumn("E_avg");
        ImGui::TableSetupColumn("E_min");
        ImGui::TableSetupColumn("E_max");
        ImGui::TableHeadersRow();
        for (Group& g : groups_) {
            ImGui::PushID(g.name.c_str());
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(g.name.c_str());
            ImGui::TableNextColumn();
            if (g.textured) {
                ImGui::TextDisabled("textured");
            } else {
                ImGui::ColorButton("##swatch", ImVec4(g.rho[0], g.rho[1], g.rho[2], 1),
                                   ImGuiColorEditFlags_NoTooltip);
                ImGui::SameLine();
                ImGui::SetNextItemWidth(150);
                ImGui::SliderFloat3("##rho", g.rho, 0.0f, 0.99f, "%.2f");
                if (ImGui::IsItemDeactivatedAfterEdit()) {
                    const dvec3 rho(g.rho[0], g.rho[1], g.rho[2]);
                    apply([&] { solver.set_reflectance(g.name, rho); });
                    g.applied = dvec3(std::nan("")); // the next frame shows the scene's
                }
            }
            for (const dvec3& E : {g.stats.E_avg, g.stats.E_min, g.stats.E_max}) {
                ImGui::TableNextColumn();
                ImGui::Text("%.4g %s", shown(E, stats.lux), unit);
            }
            ImGui::PopID();
        }
        ImGui::EndTable();
    }
    ImGui::End();

    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    return edited;
}

} // namespace hemirad::view
