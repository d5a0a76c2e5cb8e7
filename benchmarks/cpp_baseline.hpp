// Benchmark baseline: a straightforward table VM in the style of the published OpenSwarm C++ VM,
// written for benchmarks/cpp_steps.py only (not a runtime). Events are looked up by name in a
// std::map; each supervisor's tables are one flat array of (transition count, then
// event/target-high/target-low triples) per state, walked linearly from the supervisor's start to
// find the current state and then its transition; callbacks live in a std::map keyed by event.
// It runs the default semantics (level inputs, after-inputs, uniform choice, public inputs first)
// with the same xorshift32 draws, so its trace equals swarmvm's and the timing compares like work.
#ifndef SWARMVM_BENCH_BASELINE_HPP
#define SWARMVM_BENCH_BASELINE_HPP

#include <functional>
#include <map>
#include <queue>
#include <string>
#include <vector>

#include "swarmvm.hpp"

namespace baseline {

struct Callback {
    std::function<void(void*)> callback;
    std::function<unsigned char(void*)> check_input;
    void* data = nullptr;
};

class FlatVM {
public:
    explicit FlatVM(const swarmvm::Image& image, std::uint32_t seed) : rng_(seed) {
        num_events_ = image.num_events;
        for (unsigned e = 0; e < image.num_events; ++e) {
            events[image.event_name(e)] = e;
            ev_controllable_.push_back(image.controllable.test(e) ? 1 : 0);
            ev_public_.push_back(image.public_events.test(e) ? 1 : 0);
        }
        for (unsigned s = 0; s < image.num_supervisors; ++s) {
            std::vector<unsigned char> in_alphabet(image.num_events, 0);
            image.sup_alphabet[s].for_each([&](unsigned e) { in_alphabet[e] = 1; });
            sup_events_.push_back(in_alphabet);
            sup_data_pos_.push_back(sup_data_.size());
            sup_current_state_.push_back(image.sup_initial[s]);
            for (unsigned q = 0; q < image.sup_num_states[s]; ++q) {
                const unsigned g = image.sup_first_state[s] + q;
                std::vector<unsigned> evs;
                image.state_defined[g].for_each([&](unsigned e) { evs.push_back(e); });
                sup_data_.push_back(static_cast<unsigned char>(evs.size()));
                for (std::size_t r = 0; r < evs.size(); ++r) {
                    const unsigned target = image.targets[image.state_first[g] + r];
                    sup_data_.push_back(static_cast<unsigned char>(evs[r]));
                    sup_data_.push_back(static_cast<unsigned char>(target >> 8));
                    sup_data_.push_back(static_cast<unsigned char>(target & 0xFF));
                }
            }
        }
    }

    void add_check(const std::string& event, std::function<unsigned char(void*)> check) {
        callback_[static_cast<unsigned char>(events.at(event))].check_input = std::move(check);
    }

    void run_step() {
        fired.clear();
        update_input();   // public first, as SCTPub
        while (!input_buffer_.empty()) {
            const unsigned char ev = input_buffer_.front();
            input_buffer_.pop();
            make_transition(ev);
            exec_callback(ev);
        }
        std::vector<unsigned char> active;
        for (unsigned e = 0; e < num_events_; ++e) {
            if (ev_controllable_[e] && enabled(static_cast<unsigned char>(e))) active.push_back(static_cast<unsigned char>(e));
        }
        if (active.empty()) return;
        const unsigned char ev = active.size() == 1 ? active[0]
                                 : active[swarmvm::scale_below(rng_.next(), static_cast<unsigned>(active.size()))];
        make_transition(ev);
        exec_callback(ev);
    }

    std::map<std::string, std::size_t> events;
    std::vector<unsigned> fired;
    const std::vector<unsigned long>& states() const { return sup_current_state_; }

private:
    void update_input() {
        for (int pass = 1; pass >= 0; --pass) {
            for (unsigned e = 0; e < num_events_; ++e) {
                if (ev_controllable_[e] || ev_public_[e] != pass) continue;
                Callback& cb = callback_[static_cast<unsigned char>(e)];
                if (cb.check_input && cb.check_input(cb.data)) input_buffer_.push(static_cast<unsigned char>(e));
            }
        }
    }

    unsigned long get_state_position(unsigned sup, unsigned long state) const {
        unsigned long position = sup_data_pos_[sup];
        for (unsigned long s = 0; s < state; ++s) position += 1 + 3ul * sup_data_[position];
        return position;
    }

    bool enabled(unsigned char ev) const {
        for (unsigned s = 0; s < sup_events_.size(); ++s) {
            if (!sup_events_[s][ev]) continue;
            unsigned long pos = get_state_position(s, sup_current_state_[s]);
            const unsigned n = sup_data_[pos++];
            bool found = false;
            for (unsigned j = 0; j < n && !found; ++j, pos += 3) found = sup_data_[pos] == ev;
            if (!found) return false;
        }
        return true;
    }

    void make_transition(unsigned char ev) {
        fired.push_back(ev);
        for (unsigned s = 0; s < sup_events_.size(); ++s) {
            if (!sup_events_[s][ev]) continue;
            unsigned long pos = get_state_position(s, sup_current_state_[s]);
            const unsigned n = sup_data_[pos++];
            for (unsigned j = 0; j < n; ++j, pos += 3) {
                if (sup_data_[pos] == ev) {
                    sup_current_state_[s] = (static_cast<unsigned long>(sup_data_[pos + 1]) << 8) | sup_data_[pos + 2];
                    break;
                }
            }
        }
    }

    void exec_callback(unsigned char ev) {
        auto found = callback_.find(ev);
        if (found != callback_.end() && found->second.callback) found->second.callback(found->second.data);
    }

    unsigned num_events_ = 0;
    std::vector<unsigned char> ev_controllable_, ev_public_;
    std::vector<std::vector<unsigned char>> sup_events_;
    std::vector<unsigned long> sup_data_pos_, sup_current_state_;
    std::vector<unsigned char> sup_data_;
    std::map<unsigned char, Callback> callback_;
    std::queue<unsigned char> input_buffer_;
    swarmvm::XorShift32 rng_;
};

}  // namespace baseline

#endif
