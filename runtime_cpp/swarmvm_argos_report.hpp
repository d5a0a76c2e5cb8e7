// What a generated ARGoS controller reports about its VM, set by the <report> element of the
// controller's <params> in the .argos file (every attribute optional, all off by default):
//
//   <report trace="true" summary="true" script="events.txt" />
//
// - trace:   after each control step, LOG the step's canonical trace line (docs/conformance.md)
//            as "trace <robot id> <line>": the line `swarmvm trace` prints for the same script,
//            options and seed.
// - summary: when the controller is destroyed (end of the experiment), LOG one line
//            "summary <robot id>: N steps, K events fired (EV_a n, ...), V violations" (no
//            parenthesis when none fired).
// - script:  replay an event script (the text `swarmvm script` writes) instead of the
//            controller's checks: row k gives the uncontrollable events of step k; past the
//            last row none occurs. The actions still run. This is test support: it is how the
//            conformance test compares the controller in real ARGoS with the reference VM.
#ifndef SWARMVM_ARGOS_REPORT_HPP
#define SWARMVM_ARGOS_REPORT_HPP

#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <argos3/core/utility/configuration/argos_configuration.h>
#include <argos3/core/utility/logging/argos_log.h>

#include "swarmvm_argos.hpp"

namespace swarmvm {

// An event script is read whole, as the Python app reads its own (swarmvm_app.MAX_SCRIPT_BYTES):
// 16 MiB hold over a million steps of a few events each.
constexpr std::size_t kMaxScriptSize = std::size_t{16} << 20;

class ArgosReport {
public:
    // Reads <report> from the controller's params (absent: nothing reported) and, with a
    // script, binds every uncontrollable check of `vm` to it. Call after the controller has
    // bound its own checks. Throws std::runtime_error / std::invalid_argument on a bad script, FileError
    // (a std::runtime_error, one line) when the script is not a regular file or is over kMaxScriptSize.
    void init(argos::TConfigurationNode& params, const std::string& robot_id, ArgosVM& vm) {
        id_ = robot_id;
        fired_count_.assign(vm.image().num_events, 0);
        if (!argos::NodeExists(params, "report")) return;
        argos::TConfigurationNode& report = argos::GetNode(params, "report");
        argos::GetNodeAttributeOrDefault(report, "trace", trace_, trace_);
        argos::GetNodeAttributeOrDefault(report, "summary", summary_, summary_);
        std::string path;
        argos::GetNodeAttributeOrDefault(report, "script", path, path);
        if (path.empty()) return;
        std::istringstream in(read_regular_file(path, kMaxScriptSize, "event script"));
        script_ = read_event_script(vm.image(), in);
        bind_script_checks(vm, row_);
        reset();
    }

    // Back to step 0, with the VM's reset.
    void reset() {
        step_ = 0;
        row_ = script_.empty() ? nullptr : &script_[0];
        fired_count_.assign(fired_count_.size(), 0);
    }

    // After each VM step, with the events it fired: the trace line, the counts, the next row.
    void record(const ArgosVM& vm, const std::vector<unsigned>& fired) {
        ++step_;
        row_ = step_ < script_.size() ? &script_[step_] : nullptr;
        for (unsigned e : fired) ++fired_count_[e];
        if (!trace_) return;
        std::vector<std::string> names;
        for (unsigned e : fired) names.push_back(vm.image().event_name(e));
        argos::LOG << "trace " << id_ << " " << format_trace_line(step_, names, vm.states(), vm.violations())
                   << std::endl;
    }

    // The summary line, if asked for; the controller calls it from Destroy().
    void finish(const ArgosVM& vm) const {
        if (!summary_) return;
        std::uint64_t total = 0;
        std::string counts;
        for (unsigned e = 0; e < fired_count_.size(); ++e) {
            if (fired_count_[e] == 0) continue;
            total += fired_count_[e];
            counts += (counts.empty() ? "" : ", ") + vm.image().event_name(e) + " " + std::to_string(fired_count_[e]);
        }
        if (!counts.empty()) counts = " (" + counts + ")";
        argos::LOG << "summary " << id_ << ": " << step_ << " steps, " << total << " events fired" << counts << ", "
                   << vm.violations() << " violations" << std::endl;
    }

private:
    std::string id_;
    bool trace_ = false;
    bool summary_ = false;
    std::vector<Mask> script_;
    const Mask* row_ = nullptr;   // the script row of the next step; read by the bound checks
    unsigned step_ = 0;
    std::vector<std::uint64_t> fired_count_;
};

}  // namespace swarmvm

#endif  // SWARMVM_ARGOS_REPORT_HPP
