// The options table of EvalOptions (docs/configuration.md is generated from it).
#include "edgevio/eval/eval_options.h"

namespace edgevio::eval {

EDGEVIO_OPTIONS_TABLE(EvalOptions,
    number("association_tolerance_s", &S::association_tolerance_s, 0.01, "s", "largest |t_est - t_gt| for two poses to be matched",
           above(0)),
    choice("alignment", &S::alignment, AlignmentKind::kSe3, kAlignmentChoices, "alignment of the estimate before the ATE"),
    number("rpe_deltas_m", &S::rpe_deltas_m, {1.0, 5.0}, "m", "travelled-distance deltas of the RPE (evo's pairing)", above(0)),
    number("are_segments_percent", &S::are_segments_percent, {10.0, 20.0, 30.0, 40.0, 50.0}, "%",
           "ARE segment lengths in percent of the trajectory's length", Range{0, 100, true, false}),
    number("are_segments_m", &S::are_segments_m, {}, "m", "ARE segment lengths in metres; when not empty they replace the percentages",
           above(0)))

}  // namespace edgevio::eval
