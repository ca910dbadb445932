// The default view of a scene that brings no camera (an OBJ file): a camera that shows its lit
// surfaces, found by casting a coarse grid of rays from a few candidate cameras.
//
// Candidates: six views from outside, each framing the bounding box from one side (looking
// along +z, -z, +x, -x, down, up), and four from inside, one from each vertical corner of the
// box at mid-height looking across it to its centre (90 degrees wide). Each is scored on a kGrid x
// kGrid grid of rays through its image: a ray whose nearest hit (either side) is the front of a
// polygon counts that polygon's weight — 1 if it emits or faces an emitter that faces it (a cheap
// test of direct light, without occlusion), 0.25 if it can only be lit indirectly, 0 if it is black
// (rho 0, no emission); a ray that meets the back of a polygon first, or nothing, counts 0. The
// score is the mean weight: the part of the image that would show lit surfaces even if the backs of
// polygons were drawn.
//
// The best outside view is chosen unless it shows less than kMinShown, or less than half of
// what the best inside view shows (a closed room: from outside, every ray meets a wall's
// back); then the best inside view. If neither shows anything (say, an inside view lands in a
// closed piece of furniture), the view that shows most with backs culled (what the renderer
// draws by default) is taken, the ray passing through the backs it meets.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "ff/bvh.h"
#include "hemirad/render.h"

namespace hemirad {

namespace {

constexpr int kGrid = 32;            ///< rays per side of a candidate's image
constexpr double kOutsideFov = 40.0; ///< [degrees] vertical, the views from outside
constexpr double kInsideFov = 90.0;  ///< [degrees] vertical, the views from inside
constexpr double kMinShown = 0.05;   ///< least score for a view to count as showing something
constexpr int kMaxEmitters = 64;     ///< emitters used in the direct-light test (most powerful)

struct Candidate {
    Camera camera;
    bool inside = false;
    double shown = 0;        ///< score with the backs of polygons drawn (black)
    double shown_culled = 0; ///< score with them culled
};

/// How lit a polygon will look: see the header comment.
class LitWeights {
  public:
    explicit LitWeights(const Scene& s) : scene_(s), weight_(s.polygons.size(), -1.f) {
        std::vector<std::pair<double, std::uint32_t>> emitters;
        for (std::uint32_t i = 0; i < s.polygons.size(); ++i) {
            const dvec3 p = s.material_of(s.polygons[i]).exitance() * s.polygons[i].area;
            const double power = p.x + p.y + p.z;
            if (power > 0) emitters.emplace_back(-power, i);
        }
        std::sort(emitters.begin(), emitters.end());
        if (emitters.size() > std::size_t(kMaxEmitters)) emitters.resize(kMaxEmitters);
        for (const auto& e : emitters) emitters_.push_back(e.second);
    }

    float operator()(std::uint32_t p) {
        float& w = weight_[p];
        if (w >= 0) return w;
        const Polygon& q = scene_.polygons[p];
        const Material& m = scene_.material_of(q);
        if (m.emits()) return w = 1.f;
        if (!(std::max({m.rho.x, m.rho.y, m.rho.z}) > 0)) return w = 0.f;
        const dvec3 c = q.centroid();
        for (std::uint32_t e : emitters_) {
            const Polygon& l = scene_.polygons[e];
            const dvec3 d = c - l.centroid();
            if (glm::dot(l.normal, d) > 0 && glm::dot(q.normal, d) < 0) return w = 1.f;
        }
        return w = 0.25f;
    }

  private:
    const Scene& scene_;
    std::vector<std::uint32_t> emitters_;
    std::vector<float> weight_;
};

Camera make_camera(const dvec3& eye, const dvec3& dir, const dvec3& up, double fov) {
    Camera c;
    c.eye = eye;
    c.target = eye + dir;
    c.up = up;
    c.fov_y_deg = fov;
    return c;
}

std::vector<Candidate> candidates(const Bounds& b) {
    const dvec3 centre = 0.5 * (b.lo + b.hi);
    const double diagonal = std::max(b.diagonal(), 1e-300);
    // A zero extent (a flat scene) counts as a sliver, so that distances stay positive.
    const dvec3 extent = glm::max(b.hi - b.lo, dvec3(1e-6 * diagonal));
    std::vector<Candidate> out;
    const double t = std::tan(0.5 * kOutsideFov * std::numbers::pi / 180);
    // Outside: looking along +z first (from the -z side, the view hemirad always had).
    const int order[6][2] = {{2, +1}, {2, -1}, {0, +1}, {0, -1}, {1, -1}, {1, +1}};
    for (const auto& [axis, sign] : order) {
        dvec3 dir(0.0);
        dir[axis] = sign;
        const dvec3 up = axis == 1 ? dvec3(0, 0, -sign) : dvec3(0, 1, 0);
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        const double half = 0.5 * std::max(extent[u], extent[v]);
        const double distance = 0.5 * extent[axis] + 1.05 * half / t;
        out.push_back({make_camera(centre - distance * dir, dir, up, kOutsideFov), false});
    }
    // Inside: from each vertical corner (8 % of the box in from both walls, at mid-height)
    // across the room to its centre, wide-angle, the way a room is photographed: two walls,
    // the floor, the ceiling and what hangs from it.
    const double fx[4] = {0.08, 0.92, 0.08, 0.92}, fz[4] = {0.08, 0.08, 0.92, 0.92};
    for (int k = 0; k < 4; ++k) {
        const dvec3 eye = b.lo + extent * dvec3(fx[k], 0.5, fz[k]);
        const dvec3 target = centre;
        out.push_back(
            {make_camera(eye, glm::normalize(target - eye), dvec3(0, 1, 0), kInsideFov), true});
    }
    return out;
}

void score(Candidate& c, const Bvh& bvh, LitWeights& weight) {
    const Camera& cam = c.camera;
    const dvec3 forward = glm::normalize(cam.target - cam.eye);
    const dvec3 right = glm::normalize(glm::cross(forward, cam.up));
    const dvec3 up = glm::cross(right, forward);
    const double t = std::tan(0.5 * cam.fov_y_deg * std::numbers::pi / 180);
    double shown = 0, culled = 0;
    for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i) {
            const double x = (2 * (i + 0.5) / kGrid - 1) * t;
            const double y = (1 - 2 * (j + 0.5) / kGrid) * t;
            const dvec3 dir = glm::normalize(forward + x * right + y * up);
            Hit hit;
            if (!bvh.intersect(cam.eye, dir, 1e300, hit)) continue;
            if (hit.front) {
                const double w = weight(hit.polygon);
                shown += w;
                culled += w;
                continue;
            }
            // Culled: pass through the backs (a few at most: walls, then furniture).
            dvec3 origin = cam.eye;
            for (int k = 0; k < 8 && !hit.front; ++k) {
                origin += hit.t * dir;
                const std::uint32_t skip = hit.polygon;
                if (!bvh.intersect(origin, dir, 1e300, hit, skip)) break;
                if (hit.front) culled += weight(hit.polygon);
            }
        }
    c.shown = shown / (kGrid * kGrid);
    c.shown_culled = culled / (kGrid * kGrid);
}

} // namespace

Camera frame_scene(const Scene& scene) {
    std::vector<Candidate> all = candidates(scene.bounds());
    if (scene.polygons.empty()) return all[0].camera;
    const Bvh bvh(scene);
    LitWeights weight(scene);
    for (Candidate& c : all) score(c, bvh, weight);
    const auto best = [&](auto key, auto keep) {
        const Candidate* b = nullptr;
        for (const Candidate& c : all)
            if (keep(c) && (!b || key(c) > key(*b))) b = &c;
        return b;
    };
    const auto shown = [](const Candidate& c) { return c.shown; };
    const Candidate* out = best(shown, [](const Candidate& c) { return !c.inside; });
    const Candidate* in = best(shown, [](const Candidate& c) { return c.inside; });
    const Candidate* chosen = nullptr;
    if (out->shown >= kMinShown && out->shown >= 0.5 * in->shown)
        chosen = out;
    else if (in->shown >= kMinShown)
        chosen = in;
    else
        chosen = best([](const Candidate& c) { return c.shown_culled; },
                      [](const Candidate&) { return true; });
    Camera c = chosen->camera;
    c.name = "default";
    return c;
}

Camera default_camera(const Scene& scene) {
    if (!scene.cameras.empty()) return scene.cameras[0];
    return frame_scene(scene);
}

} // namespace hemirad
