// The viewer's camera: orbit about a target (yaw, pitch, distance about the start camera's up
// axis), pan, zoom and fly. Produces a hemirad::Camera for SolutionRenderer. No GL here.
#pragma once

#include <algorithm>
#include <cmath>

#include "hemirad/scene.h"

namespace hemirad::view {

class OrbitCamera {
  public:
    /// Starts at `start` (and returns to it on reset()); `scene_size` [scene units] scales
    /// pan, zoom limits and fly speed.
    OrbitCamera(const Camera& start, double scene_size) : start_(start), size_(scene_size) {
        reset();
    }

    void reset() {
        up_ = safe_normalize(start_.up, {0, 1, 0});
        target_ = start_.target;
        fov_ = start_.fov_y_deg;
        const dvec3 d = start_.eye - start_.target;
        distance_ = std::max(glm::length(d), 1e-9);
        set_direction(d / distance_);
        moved_ = false;
    }

    /// Left drag: dx, dy in pixels of a window `height` pixels tall (a drag over the window's
    /// height turns by about 180 degrees).
    void orbit(double dx, double dy, double height) {
        const double k = M_PI / std::max(height, 1.0);
        yaw_ -= dx * k;
        pitch_ = std::clamp(pitch_ + dy * k, -kMaxPitch, kMaxPitch);
        moved_ = true;
    }
    /// Right/middle drag: the point under the cursor follows it (at the target's depth).
    void pan(double dx, double dy, double height) {
        const double per_pixel =
            2.0 * distance_ * std::tan(0.5 * fov_ * M_PI / 180.0) / std::max(height, 1.0);
        const dvec3 f = -direction();
        const dvec3 right = safe_normalize(glm::cross(f, up_), {1, 0, 0});
        const dvec3 up = glm::cross(right, f);
        target_ += (-dx * right + dy * up) * per_pixel;
        moved_ = true;
    }
    /// Wheel: each notch moves 10% closer (positive) or farther (negative).
    void zoom(double notches) {
        distance_ = std::clamp(distance_ * std::pow(0.9, notches), 1e-4 * size_, 100.0 * size_);
        moved_ = true;
    }
    /// Fly: forward (along the view), right, up (along the up axis), in units of the scene
    /// size; moves eye and target together.
    void fly(double forward, double right, double up) {
        const dvec3 f = -direction();
        const dvec3 r = safe_normalize(glm::cross(f, up_), {1, 0, 0});
        target_ += (forward * f + right * r + up * up_) * size_;
        moved_ = true;
    }
    /// Looks at the whole of `b` from the current direction.
    void frame(const Bounds& b, double aspect) {
        target_ = 0.5 * (b.lo + b.hi);
        const double radius = std::max(0.5 * b.diagonal(), 1e-9);
        const double half = 0.5 * fov_ * M_PI / 180.0;
        const double half_min = std::min(half, std::atan(std::tan(half) * std::max(aspect, 1e-3)));
        distance_ = radius / std::sin(half_min);
        moved_ = true;
    }

    /// The camera now; exactly the start camera until the first move.
    Camera camera() const {
        if (!moved_) return start_;
        Camera c = start_;
        c.name = "viewer";
        c.target = target_;
        c.eye = target_ + distance_ * direction();
        c.up = up_;
        c.fov_y_deg = fov_;
        return c;
    }

  private:
    static constexpr double kMaxPitch = 89.0 * M_PI / 180.0;

    static dvec3 safe_normalize(const dvec3& v, const dvec3& fallback) {
        const double l = glm::length(v);
        return l > 1e-12 ? v / l : fallback;
    }
    /// Unit vector from the target to the eye.
    dvec3 direction() const {
        return std::cos(pitch_) * (std::cos(yaw_) * e1_ + std::sin(yaw_) * e2_) +
               std::sin(pitch_) * up_;
    }
    void set_direction(const dvec3& d) {
        pitch_ = std::asin(std::clamp(glm::dot(d, up_), -1.0, 1.0));
        pitch_ = std::clamp(pitch_, -kMaxPitch, kMaxPitch);
        dvec3 flat = d - glm::dot(d, up_) * up_;
        // Looking straight along the up axis: any horizontal reference will do.
        const dvec3 any = std::abs(up_.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 0, 1);
        e1_ = safe_normalize(flat, safe_normalize(any - glm::dot(any, up_) * up_, {1, 0, 0}));
        e2_ = glm::cross(up_, e1_);
        yaw_ = 0;
    }

    Camera start_;
    double size_;
    dvec3 up_{0, 1, 0}, e1_{1, 0, 0}, e2_{0, 0, 1}, target_{0.0};
    double yaw_ = 0, pitch_ = 0, distance_ = 1, fov_ = 40;
    bool moved_ = false;
};

} // namespace hemirad::view
