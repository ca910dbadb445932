// hemirad-bench experiment viewer_frames (viewer_frames.cpp).
#pragma once

namespace hemirad::bench {

/// hemirad-view on a furnished floor of ~1e5 triangles, solving 40 shots on its own thread
/// while it draws (960 x 720, under xvfb-run when there is no display): the frame time it
/// reports. Prints its "JSON ..." and "ROW ..." lines.
void run_viewer_frames();

} // namespace hemirad::bench
