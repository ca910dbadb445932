// The reference's probe CSV (reference.h).
#include <sstream>

#include "hemirad/error.h"
#include "hemirad/reference.h"

namespace hemirad {

std::string reference_csv(const Scene& scene, const std::vector<Probe>& probes,
                          const std::vector<ReferenceValue>& values) {
    HEMIRAD_CHECK_EQ(probes.size(), values.size());
    std::ostringstream s;
    s.precision(9);
    s << "x,y,z,nx,ny,nz,E_r,E_g,E_b,polygon,group,sem_r,sem_g,sem_b\n";
    for (std::size_t i = 0; i < probes.size(); ++i) {
        const Probe& p = probes[i];
        const ReferenceValue& v = values[i];
        s << p.position.x << "," << p.position.y << "," << p.position.z << "," << p.normal.x << ","
          << p.normal.y << "," << p.normal.z << "," << v.E.x << "," << v.E.y << "," << v.E.z << ",";
        if (v.on_surface)
            s << v.polygon << "," << scene.groups[scene.polygons[v.polygon].group];
        else
            s << ",none";
        s << "," << v.sem.x << "," << v.sem.y << "," << v.sem.z << "\n";
    }
    return s.str();
}

} // namespace hemirad
