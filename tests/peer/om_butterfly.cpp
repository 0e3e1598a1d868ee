// om_butterfly: the OpenMesh side of fairsub's modified butterfly comparison
// (tests/peer_sqrt3_butterfly.rs). Reads a triangle net (tri_io.h), applies
// OpenMesh::Subdivider::Uniform::ModifiedButterflyT L times on a TriMesh whose points are
// Vec3d (double precision, RealType double; Debian libopenmesh-dev) and writes the result.
//
//   om_butterfly L IN.obj OUT.txt
#include "tri_io.h"
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/ModifiedButterFlyT.hh>

struct DoubleTraits : public OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
};
typedef OpenMesh::TriMesh_ArrayKernelT<DoubleTraits> Mesh;

int main(int argc, char** argv) {
    if (argc != 4) tri_fail("usage: om_butterfly LEVELS IN.obj OUT.txt");
    int levels = std::atoi(argv[1]);
    TriInput t = read_obj(argv[2]);
    Mesh m;
    std::vector<Mesh::VertexHandle> vs;
    for (auto& p : t.points) vs.push_back(m.add_vertex(Mesh::Point(p[0], p[1], p[2])));
    for (size_t i = 0; i < t.faces.size(); ++i) {
        std::vector<Mesh::VertexHandle> f;
        for (int c : t.faces[i]) f.push_back(vs[c]);
        if (!m.add_face(f).is_valid())
            tri_fail("face " + std::to_string(i) + " cannot be added (non-manifold?)");
    }
    OpenMesh::Subdivider::Uniform::ModifiedButterflyT<Mesh, double> sub;
    sub.attach(m);
    sub(levels);
    sub.detach();
    std::vector<std::array<double, 3>> pts;
    for (auto v : m.vertices()) {
        const auto& p = m.point(v);
        pts.push_back({p[0], p[1], p[2]});
    }
    std::vector<std::vector<int>> faces;
    for (auto f : m.faces()) {
        std::vector<int> c;
        for (auto v : m.fv_range(f)) c.push_back(v.idx());
        faces.push_back(c);
    }
    write_tri(argv[3], pts, faces);
    return 0;
}
