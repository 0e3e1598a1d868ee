// The OpenCASCADE peer of tests/step_peer.rs: reads a STEP file with OpenCASCADE's
// STEPControl_Reader (the reader FreeCAD uses) and prints what a CAD user would check, as one
// JSON object on stdout:
//
//   faces_in_file    ADVANCED_FACE instances the reader saw (its entity count by type)
//   faces            faces of the transferred shape
//   solids, shells   solids and shells of the shape; closed_shells: shells BRep_Tool calls closed
//   valid            BRepCheck_Analyzer(shape).IsValid()
//   free_edges       edges of the shape used by one face only (no sewing is done)
//   volume, area     BRepGProp::VolumeProperties (only when there are solids, else 0) /
//                    SurfaceProperties, adaptive to EPS
//   volume_error     the error estimates BRepGProp returns, and gprop_seconds its time
//   centroid         the volume's centre of mass (the surface's for an open shell)
//   read_seconds     wall time of parsing the file; seconds: of parsing and transferring
//                    (the reader's shape healing included); check_seconds: of
//                    BRepCheck_Analyzer
//
// Usage: occt_step FILE.step [EPS]   (EPS: relative error of the integrals, default 1e-12;
//        0: no integrals)
// Built by tests/peer/build.sh against Debian's libocct-*-dev (OpenCASCADE 7.6).

#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Reader.hxx>
#include <StepData_StepModel.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Shell.hxx>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

static int count(const TopoDS_Shape& s, TopAbs_ShapeEnum t) {
    int n = 0;
    for (TopExp_Explorer e(s, t); e.More(); e.Next()) ++n;
    return n;
}

int main(int argc, char** argv) {
    if (argc < 2 || argc > 3) {
        std::fprintf(stderr, "usage: occt_step FILE.step [EPS]\n");
        return 2;
    }
    auto t0 = std::chrono::steady_clock::now();
    STEPControl_Reader reader;
    if (reader.ReadFile(argv[1]) != IFSelect_RetDone) {
        std::fprintf(stderr, "occt_step: cannot read %s\n", argv[1]);
        return 1;
    }
    double read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    int in_file = 0;
    Handle(StepData_StepModel) model = reader.StepModel();
    for (int i = 1; i <= model->NbEntities(); ++i) {
        if (std::string(model->Entity(i)->DynamicType()->Name()) == "StepShape_AdvancedFace") ++in_file;
    }
    reader.TransferRoots();
    TopoDS_Shape shape = reader.OneShape();
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (shape.IsNull()) {
        std::fprintf(stderr, "occt_step: %s gave no shape\n", argv[1]);
        return 1;
    }
    int closed = 0;
    for (TopExp_Explorer e(shape, TopAbs_SHELL); e.More(); e.Next()) {
        if (BRep_Tool::IsClosed(TopoDS::Shell(e.Current()))) ++closed;
    }
    TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
    TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
    int free_edges = 0;
    for (int i = 1; i <= edge_faces.Extent(); ++i) {
        if (BRep_Tool::Degenerated(TopoDS::Edge(edge_faces.FindKey(i)))) continue;
        if (edge_faces(i).Extent() < 2) ++free_edges;
    }
    auto tc = std::chrono::steady_clock::now();
    bool valid = BRepCheck_Analyzer(shape).IsValid();
    double check_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tc).count();
    GProp_GProps vol, surf;
    // adaptive Gauss integration to a relative error of eps (the default rules of fixed order
    // are off by 1e-8 on these surfaces)
    double eps = argc > 2 ? std::atof(argv[2]) : 1e-12;
    auto tg = std::chrono::steady_clock::now();
    double vol_err = 0, area_err = 0;
    int solids = count(shape, TopAbs_SOLID);
    if (eps > 0) {  // EPS 0: no properties (timing runs)
        // an open shell encloses nothing: its volume is not asked for (half the time)
        if (solids > 0) vol_err = BRepGProp::VolumeProperties(shape, vol, eps);
        area_err = BRepGProp::SurfaceProperties(shape, surf, eps);
    }
    double gprop_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tg).count();
    gp_Pnt c = eps <= 0 ? gp_Pnt() : solids > 0 ? vol.CentreOfMass() : surf.CentreOfMass();
    std::printf(
        "{\"faces_in_file\": %d, \"faces\": %d, \"solids\": %d, \"shells\": %d, "
        "\"closed_shells\": %d, \"valid\": %s, \"free_edges\": %d, \"volume\": %.17g, "
        "\"area\": %.17g, \"centroid\": [%.17g, %.17g, %.17g], \"volume_error\": %.3g, \"area_error\": %.3g, "
        "\"read_seconds\": %.3f, \"seconds\": %.3f, \"check_seconds\": %.3f, \"gprop_seconds\": %.3f}\n",
        in_file, count(shape, TopAbs_FACE), solids, count(shape, TopAbs_SHELL), closed,
        valid ? "true" : "false", free_edges, vol.Mass(), surf.Mass(), c.X(), c.Y(), c.Z(),
        vol_err, area_err, read_seconds, seconds, check_seconds, gprop_seconds);
    return 0;
}
