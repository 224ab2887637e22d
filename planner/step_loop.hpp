#pragma once
// The fill loop, written once for every step source: asks the source for steps while nothing is
// staged, hands each to the edge emitter and keeps the motion's progress. A source runs it with
// its own type (StepSource::plan: `return loop.run(*this);`), so the per-step call is a direct
// one — one virtual call per fill, not per step (the planner's step rate is its bench figure).
#include "planner/edge_emitter.hpp"
#include "planner/step_source.hpp"

namespace stepmod::planner {

class StepLoop {
 public:
  // `active`: the motion is still being planned (cleared when it ends); `now`: the planning time
  // on the motion's time base; steps are planned up to `horizon`. `st` receives the answer that
  // ended the loop (kLater: the step left unplanned).
  StepLoop(StepProgress& at, bool& active, EdgeEmitter& out, Nanos now, Nanos horizon,
           SourceStep& st) noexcept
      : at_(at), active_(active), out_(out), now_(now), horizon_(horizon), st_(st) {}

  template <class Source>
  Answer run(Source& source) noexcept {
    // The progress and the active flag are worked on in locals and written back once: through
    // the references, every edge the emitter stores could alias them, and the compiler would
    // reload and store them at each step (the planner's step rate is its bench figure).
    StepProgress at = at_;
    bool active = active_;
    Answer a = Answer::kStep;
    SourceStep st;  // a local: the per-step answer stays in registers
    while (active && out_.staged_empty()) {
      a = source.next(at, StepWindow{now_, horizon_, out_.last_t()}, st);
      if (a == Answer::kLater) {
        out_.rest(st.t);  // left unplanned, so that a hold can still replan it
        st_ = st;
        break;
      }
      if (a == Answer::kWait) break;
      if (a == Answer::kEnd) {
        active = false;
        out_.end(source.end_time(at, now_));
      } else {
        const Nanos t = out_.step(st, at.k + 1);
        ++at.k;
        at.tk = st.ts;
        at.tk_ns = t;
        if (at.k >= at.end) {
          out_.end(t);
          active = false;
        }
      }
      out_.flush(horizon_);
    }
    at_ = at;
    active_ = active;
    return a;
  }

 private:
  StepProgress& at_;
  bool& active_;
  EdgeEmitter& out_;
  Nanos now_;
  Nanos horizon_;
  SourceStep& st_;
};

}  // namespace stepmod::planner
