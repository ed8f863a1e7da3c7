// The pipeline's opening stage (nmesh/pipeline/opening.h).
#include "nmesh/pipeline/opening.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "nmesh/finish/open_surface.h"
#include "nmesh/finish/vertex_top_up.h"
#include "nmesh/finish/view_sheet.h"
#include "nmesh/mesh/mesh_pieces.h"
#include "nmesh/pipeline/finishing.h"

namespace nmesh::pipeline {

void open_output(Mesh& learnt, bool finish, bool last, std::shared_ptr<PointGrid>& cloud_index, PointSpan cloud,
                 const Normalization& norm, const Parameters& params, Reporter& reporter, Result& result) {
    Statistics& stats = result.stats;
    learnt.build_faces();
    const PointGrid& index = cloud_index_of(cloud_index, cloud, norm, params, stats);
    double area = 0.0;
    for (std::uint32_t f = 0; f < learnt.face_capacity(); ++f) {
        if (learnt.is_removed(Face(f))) continue;
        const Halfedge h = learnt.halfedge(Face(f));
        const Vec3 a = learnt.position(learnt.from(h)), b = learnt.position(learnt.to(h));
        area += 0.5 * double(nmesh::norm(cross(b - a, learnt.position(learnt.to(learnt.next(h))) - a)));
    }
    // The spacing guess: the mesh's area shared among the points (twice the sheet's on a view).
    CloudView view = view_cloud(index, float(std::sqrt(area / double(std::max<std::size_t>(index.size(), 1)))));
    view.hole_spacings = params.min_hole;
    OpenReport report;
    std::vector<Mesh> pieces;
    if (view.partial) {
        const IndexedMesh side = view_sheet(learnt, index, view, report);
        learnt = Mesh();
        for (const MeshPiece& p : split_pieces(side)) pieces.push_back(Mesh::from_indexed(p.mesh, true));
    } else {
        pieces.push_back(std::move(learnt));
    }
    std::size_t faces = 0, done = 0;
    for (const Mesh& p : pieces) faces += p.n_faces();
    stats.finished = finish;
    std::vector<IndexedMesh> shapes;
    for (Mesh& piece : pieces) {
        if (finish) {
            Mesh finished;
            const double from = double(done) / double(faces), share = double(piece.n_faces()) / double(faces);
            done += piece.n_faces();
            // A view's sheet without the repair: its few crossings are cut at the end instead
            // (the repair's rounds on them take seconds and then fall back on the sheet as it was).
            if (finish_stage(piece, cloud_index, cloud, norm, params, reporter, stats, finished, from, share, !view.partial,
                             last))
                piece = std::move(finished);
            else
                stats.finished = false;
        }
        piece.build_faces();
        shapes.push_back(piece.to_indexed());
    }
    if (view.partial) {
        // The finished sheet without the faces its relaxation turned against the view.
        const IndexedMesh sheet = cut_turned(join_pieces(shapes), index, view, report);
        pieces.clear();
        for (const MeshPiece& p : split_pieces(sheet)) pieces.push_back(Mesh::from_indexed(p.mesh, true));
    }
    const float typical = typical_edge(join_pieces(shapes));
    shapes.clear();
    for (const Mesh& piece : pieces) shapes.push_back(cut_unsupported(piece, index, view, typical, report));
    pieces.clear();
    std::uint32_t crossing = 0;
    result.mesh = last || view.partial ? cut_crossings(join_pieces(shapes), crossing) : join_pieces(shapes);
    report.removed_crossing += crossing;
    // The vertices the cuts took, given back where the edges are longest (vertex_top_up.h).
    std::uint32_t added = 0;
    result.mesh = top_up_vertices(result.mesh, params.target_vertices, added);
    stats.open_vertices_added = added;
    stats.layer_faces_removed = report.removed_layer;
    stats.open_faces_removed = report.removed_unsupported;
    stats.crossing_faces_removed = report.removed_crossing;
}

}  // namespace nmesh::pipeline
