// cgal_sqrt3: the CGAL side of fairsub's sqrt(3) comparison (tests/peer_sqrt3_butterfly.rs).
// Reads a triangle net (tri_io.h), applies CGAL::Subdivision_method_3::Sqrt3_subdivision with
// number_of_iterations(L) on a Surface_mesh over Simple_cartesian<double> (Debian libcgal-dev,
// header-only) and writes the result.
//
//   cgal_sqrt3 L IN.obj OUT.txt
#include "tri_io.h"
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/subdivision_method_3.h>

typedef CGAL::Simple_cartesian<double> K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;

int main(int argc, char** argv) {
    if (argc != 4) tri_fail("usage: cgal_sqrt3 LEVELS IN.obj OUT.txt");
    int levels = std::atoi(argv[1]);
    TriInput t = read_obj(argv[2]);
    Mesh m;
    std::vector<Mesh::Vertex_index> vs;
    for (auto& p : t.points) vs.push_back(m.add_vertex(K::Point_3(p[0], p[1], p[2])));
    for (size_t i = 0; i < t.faces.size(); ++i) {
        std::vector<Mesh::Vertex_index> f;
        for (int c : t.faces[i]) f.push_back(vs[c]);
        if (m.add_face(f) == Mesh::null_face())
            tri_fail("face " + std::to_string(i) + " cannot be added (non-manifold?)");
    }
    CGAL::Subdivision_method_3::Sqrt3_subdivision(
        m, CGAL::parameters::number_of_iterations(levels));
    m.collect_garbage();
    std::vector<std::array<double, 3>> pts;
    for (auto v : m.vertices()) {
        const auto& p = m.point(v);
        pts.push_back({p.x(), p.y(), p.z()});
    }
    std::vector<std::vector<int>> faces;
    for (auto f : m.faces()) {
        std::vector<int> c;
        for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) c.push_back((int)v.idx());
        faces.push_back(c);
    }
    write_tri(argv[3], pts, faces);
    return 0;
}
