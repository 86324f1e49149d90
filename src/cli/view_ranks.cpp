#include "cli/view_ranks.h"

#include "core/error.h"
#include "core/progress.h"
#include "gpu/shader_library.h"
#include "picture/picture.h"

#if AMRVK_MPI
#include "mpi/view_link.h"
#include "mpi/world.h"
#endif

namespace amrvk::cli {

#if AMRVK_MPI
namespace {

// The viewer's view of the other ranks: the link's passes.
class LinkPasses : public viewer::RankPasses {
public:
    explicit LinkPasses(mpi::World& world) : mLink(world) {}
    int ranks() const override { return mLink.ranks(); }
    void start(const picture::Picture& p) override { mLink.start(p); }
    void pass(const picture::Picture& p, uint32_t perRank) override { mLink.pass(p, perRank); }

private:
    mpi::ViewLink mLink;
};

}  // namespace

int viewOnRanks(mpi::World& world, viewer::ViewerOptions options, std::shared_ptr<const scene::Volume> volume) {
    if (world.size() == 1) return viewer::runViewer(options, std::move(volume));
    if (world.rank() == 0) {
        options.ranks = std::make_shared<LinkPasses>(world);
        try {
            return viewer::runViewer(options, std::move(volume));
        } catch (const mpi::FollowerFailed&) {
            return 1;  // the rank that failed reports it (runOnRanks' agreement)
        }
    }
    // A follower: no window, no script, no output; the same description and data as rank 0.
    gpu::ContextOptions co = options.context;
    co.requireRayQuery = options.start.session.structure.backend == scene::Backend::Rq;
    gpu::Context ctx(co);
    const picture::Options po{.shaders = gpu::ShaderLibrary(options.shaderDir)};
    picture::Picture p = picture::makePicture(ctx, volume, options.start, po);
    mpi::followViewer(world, ctx, p, po);
    return 0;
}
#else
int viewOnRanks(mpi::World&, viewer::ViewerOptions options, std::shared_ptr<const scene::Volume> volume) {
    return viewer::runViewer(options, std::move(volume));
}
#endif

}  // namespace amrvk::cli
