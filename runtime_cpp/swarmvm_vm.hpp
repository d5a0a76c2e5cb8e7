// swarmvm C++ VM: evolves compiled supervisors from a swarmvm table image.
//
// Header only, C++17, standard library only. It implements docs/semantics.md exactly and is
// checked trace for trace against the Python reference (runtime_py/swarmvm_reference.py), whose
// names it mirrors: BasicVM::step, XorShift32, replay, format_trace_line; the step's stages are
// named as in every runtime (docs/semantics.md, "One step in each runtime"). The tables always
// come from a table image (swarmvm_image.hpp): compiled in as a byte array or read from a .svm
// file, both go through Image::parse and its checks, so "compiled in" and "loaded" are one code
// path. swarmvm.hpp includes it with the compatibility layer (swarmvm_compat.hpp).
#ifndef SWARMVM_VM_HPP
#define SWARMVM_VM_HPP

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <istream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "swarmvm_image.hpp"

namespace swarmvm {

constexpr std::uint32_t kZeroSeed = 0x9E3779B9u;
// The violation counter stops here on every runtime (docs/semantics.md).
constexpr std::uint32_t kMaxViolations = 0xFFFFFFFFu;

// A check, an action or the violation hook threw; the original exception is nested
// (std::rethrow_if_nested).
// The policy (docs/semantics.md, "Callbacks that raise"), as the Python VM's CallbackError: a
// check that throws ends the step before any transition, so the VM is as it was before the
// step; an action that throws ends the step after its own event's transition, which stays
// applied. Either way the next step() runs normally.
class CallbackError : public std::runtime_error {
public:
    CallbackError(std::string event, std::string kind, const std::string& cause)
        : std::runtime_error("the " + kind + " of " + event + " threw: " + cause),
          event_(std::move(event)), kind_(std::move(kind)) {}
    const std::string& event() const { return event_; }   // the event's name
    const std::string& kind() const { return kind_; }     // "check", "action" or "violation hook"

private:
    std::string event_;
    std::string kind_;
};

// Options of docs/semantics.md. The learned policy is not implemented by this runtime:
// parse_policy refuses it.
enum class Inputs { level, edge };
enum class Control { after_inputs, if_quiet };
enum class Policy { uniform, first, weighted };

struct Options {
    Inputs inputs = Inputs::level;
    Control control = Control::after_inputs;
    Policy policy = Policy::uniform;
    std::uint32_t seed = 1;
    std::vector<std::string> priority;   // policy first: events ranked first, highest first
};

inline Inputs parse_inputs(const std::string& text) {
    if (text == "level") return Inputs::level;
    if (text == "edge") return Inputs::edge;
    throw std::invalid_argument("inputs must be level or edge, not '" + text + "'");
}

inline Control parse_control(const std::string& text) {
    if (text == "after-inputs") return Control::after_inputs;
    if (text == "if-quiet") return Control::if_quiet;
    throw std::invalid_argument("control must be after-inputs or if-quiet, not '" + text + "'");
}

inline Policy parse_policy(const std::string& text) {
    if (text == "uniform") return Policy::uniform;
    if (text == "first") return Policy::first;
    if (text == "weighted") return Policy::weighted;
    if (text == "learned") throw std::invalid_argument("policy 'learned' is not implemented by the C++ runtime");
    throw std::invalid_argument("policy must be uniform, first or weighted, not '" + text + "'");
}

// The one pseudo-random generator of every runtime (Marsaglia's xorshift32, 13/17/5).
// Seed 0, a fixed point of xorshift, is replaced by 0x9E3779B9.
class XorShift32 {
public:
    explicit XorShift32(std::uint32_t seed = 1) { this->seed(seed); }
    void seed(std::uint32_t seed) { state_ = seed != 0 ? seed : kZeroSeed; }
    std::uint32_t next() {
        std::uint32_t x = state_;
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        state_ = x;
        return x;
    }
    // The draw next() would return, the state advanced only if `advance`: without a branch.
    std::uint32_t next_if(bool advance) {
        const std::uint32_t before = state_, x = next();
        state_ ^= (x ^ before) & (0u - std::uint32_t{!advance});
        return x;
    }

private:
    std::uint32_t state_ = 1;
};

// An index in [0, n) for n < 65536 from a 32-bit draw: the top 16 bits scaled by n.
inline unsigned scale_below(std::uint32_t draw, unsigned n) {
    return static_cast<unsigned>(((draw >> 16) * n) >> 16);
}

// The uniform policy's index among n choices: no draw unless n > 1 (docs/semantics.md).
// `varies`: whether n > 1 in some steps and not in others (a hint, see the XorShift32 overload).
template <class Rng>
unsigned pick_uniform(Rng& rng, unsigned n, bool /*varies*/) {
    return n > 1 ? scale_below(rng.next(), n) : 0;
}

// The same for the specified generator. When n > 1 in some steps and not in others, a branch
// on it is as good as random to a predictor: the next state is then computed in every step and
// kept only if n > 1 (scale_below(draw, n) is 0 for n <= 1). Otherwise the branch always goes
// the same way, and drawing in every step would only lengthen the step.
inline unsigned pick_uniform(XorShift32& rng, unsigned n, bool varies) {
    if (!varies) return n > 1 ? scale_below(rng.next(), n) : 0;
    return scale_below(rng.next_if(n > 1), n);
}

// A member function as a VM callback: vm.set_action("EV_x", member(this, &C::OnX)) or
// vm.set_check("EV_y", member(this, &C::CheckY)), the method taking the event's data pointer.
template <class C, class R>
auto member(C* object, R (C::*method)(void*)) {
    return [object, method](void* data) { return (object->*method)(data); };
}

// The virtual machine: current states, inputs, generator, callbacks; step() evolves it.
// Rng is any type with seed(uint32_t) and uint32_t next(); the default is the specified
// xorshift32 (swarmvm_argos.hpp offers ARGoS's CRNG instead).
template <class Rng = XorShift32>
class BasicVM {
public:
    using Action = std::function<void(void*)>;
    using Check = std::function<bool(void*)>;
    using ViolationHook = std::function<void(unsigned event, unsigned supervisor)>;

    explicit BasicVM(Image image, Options options = Options(), Rng rng = Rng())
        : options_(std::move(options)), rng_(std::move(rng)) {
        Derived derived = derive(image, options_);
        image_ = std::move(image);
        derived_ = std::move(derived);
        actions_.assign(image_.num_events, Action());
        checks_.assign(image_.num_events, Check());
        check_calls_.assign(image_.num_events, CheckCall());
        data_.assign(image_.num_events, nullptr);
        fired_.reserve(image_.num_events);
        reset();
    }

    // Swaps in a new image between two steps; states restart from its initial states.
    // Callbacks bound by name are rebound by name; a name the new image lacks throws
    // UnknownEvent before anything changes, so the VM keeps running the logic it had. An
    // action may load an image during a step, which then ends after that action (nothing else
    // fires in it: docs/semantics.md, "Reset and swap"); a check or the violation hook may not
    // (std::logic_error).
    void load(Image image) {
        refuse_while_polling("load an image");
        if (in_violation_hook_) throw std::logic_error("the violation hook cannot load an image: load it after step() returns");
        std::vector<Action> actions(image.num_events);
        std::vector<Check> checks(image.num_events);
        std::vector<CheckCall> check_calls(image.num_events);
        std::vector<void*> data(image.num_events, nullptr);
        for (unsigned e = 0; e < image_.num_events; ++e) {
            if (!actions_[e] && !checks_[e] && data_[e] == nullptr) continue;
            if (image_.has_names() && !image.has_names()) {
                throw UnknownEvent("the new image carries no event names to rebind callbacks by");
            }
            const unsigned to = image_.has_names() ? image.event_index(image_.event_name(e)) : e;
            if (to >= image.num_events) throw UnknownEvent("event index " + std::to_string(e) + " is not in the new image");
            actions[to] = actions_[e];
            checks[to] = checks_[e];
            check_calls[to] = check_calls_[e];
            data[to] = data_[e];
        }
        Derived derived = derive(image, options_);
        image_ = std::move(image);
        derived_ = std::move(derived);
        if (running_actions_ != 0) retired_actions_.push_back(std::move(actions_));   // one of them is running (act)
        actions_ = std::move(actions);
        checks_ = std::move(checks);
        check_calls_ = std::move(check_calls);
        data_ = std::move(data);
        fired_.reserve(image_.num_events);
        rebuild_polls();
        ++loads_;
        reset();
    }

    // Back to the initial states, cleared inputs and counters, generator re-seeded.
    void reset() {
        states_.assign(image_.sup_initial.begin(), image_.sup_initial.end());
        globals_.resize(states_.size());
        for (std::size_t s = 0; s < states_.size(); ++s) {
            globals_[s] = static_cast<std::uint16_t>(image_.sup_first_state[s] + states_[s]);
        }
        previous_ = Mask();
        previous_narrow_ = BasicMask<1>();
        violations_ = 0;
        rng_.seed(options_.seed);
        relocate();
    }

    // Binds an action and/or a check to an event given by name ("EV_x" or "x") or index.
    // A name the supervisor does not have throws UnknownEvent, never binds event 0.
    void bind(const std::string& event, Action action, Check check = Check(), void* data = nullptr) {
        bind(image_.event_index(event), std::move(action), std::move(check), data);
    }
    void bind(unsigned event, Action action, Check check = Check(), void* data = nullptr) {
        require(event);
        if (check && image_.controllable.test(event)) {
            throw std::invalid_argument(image_.event_name(event) + " is controllable: it takes an action, not a check");
        }
        if (check) refuse_while_polling("bind a check");
        if (action) actions_[event] = std::move(action);
        if (check) {
            checks_[event] = std::move(check);
            check_calls_[event] = CheckCall();
        }
        data_[event] = data;
        rebuild_polls();
    }
    void set_action(const std::string& event, Action action) { set_action(image_.event_index(event), std::move(action)); }
    void set_action(unsigned event, Action action) {
        require(event);
        actions_[event] = std::move(action);
        note_actions();
    }
    void set_check(const std::string& event, Check check) { set_check(image_.event_index(event), std::move(check)); }
    void set_check(unsigned event, Check check) { store_check(event, std::move(check), CheckCall()); }
    // The same for a callable of a type known here (a lambda, a function pointer): still held
    // by a Check, but the step calls it through a function pointer made for its type (one
    // direct call, its body inlined) instead of through std::function's empty test and invoker.
    template <class F, class = std::enable_if_t<!std::is_same<std::decay_t<F>, Check>::value &&
                                                !std::is_same<std::decay_t<F>, std::nullptr_t>::value &&
                                                std::is_convertible<std::invoke_result_t<F&, void*>, bool>::value>>
    void set_check(const std::string& event, F&& check) {
        set_check(image_.event_index(event), std::forward<F>(check));
    }
    template <class F, class = std::enable_if_t<!std::is_same<std::decay_t<F>, Check>::value &&
                                                !std::is_same<std::decay_t<F>, std::nullptr_t>::value &&
                                                std::is_convertible<std::invoke_result_t<F&, void*>, bool>::value>>
    void set_check(unsigned event, F&& check) {
        using Callable = std::decay_t<F>;
        store_check(event, Check(std::forward<F>(check)), CheckCall{
            [](void* callable, void* data) -> bool { return (*static_cast<Callable*>(callable))(data); },
            [](Check& owner) -> void* { return owner.template target<Callable>(); }});
    }
    void on_violation(ViolationHook hook) { on_violation_ = std::move(hook); }

    // Names of uncontrollable events with no check (they can never occur).
    std::vector<std::string> unbound_checks() const {
        std::vector<std::string> out;
        for (unsigned e : derived_.input_order) {
            if (!checks_[e]) out.push_back(image_.event_name(e));
        }
        return out;
    }

    // Controllable events enabled by every supervisor, as a mask.
    Mask enabled_mask() const { return enabled_set(derived_.wide); }

    // Controllable events enabled by every supervisor, in canonical order.
    std::vector<unsigned> enabled() const {
        std::vector<unsigned> out;
        enabled_mask().for_each([&](unsigned e) { out.push_back(e); });
        return out;
    }

    // One VM step (docs/semantics.md); returns the events that fired, in the order applied (a
    // reference valid until the next step() or load()). Images of up to 64 events step with
    // one-word sets.
    const std::vector<unsigned>& step() {
        return image_.num_events <= 64 ? step_with(derived_.narrow, previous_narrow_)
                                       : step_with(derived_.wide, previous_);
    }

    const Image& image() const { return image_; }
    const Options& options() const { return options_; }
    const std::vector<std::uint16_t>& states() const { return states_; }
    std::uint32_t violations() const { return violations_; }
    Rng& rng() { return rng_; }

private:
    // Largest successor table (states x events) built at load: 4 MB of uint32.
    static constexpr std::size_t kDenseSlots = std::size_t{1} << 20;
    static constexpr std::uint32_t kNoSuccessor = 0xFFFFFFFFu;

    // A defined successor as a transition needs it, in one word: the position of the target in
    // the target section (for its probability) above the target's global state (what enabled
    // sets and successors are indexed by). Both are below 65535, so it is never kNoSuccessor.
    static std::uint32_t successor_at(unsigned slot, unsigned global) {
        return (static_cast<std::uint32_t>(slot) << 16) | global;
    }

    // The sets a step works with, in one representation M (a BasicMask).
    template <class M>
    struct Sets {
        M controllable;
        M public_inputs, private_inputs;    // uncontrollable events: the two input classes
        std::vector<M> allowed;             // per global state: defined | not in alphabet

        Sets() = default;
        template <class Other>
        explicit Sets(const Sets<Other>& other)
            : controllable(other.controllable), public_inputs(other.public_inputs), private_inputs(other.private_inputs) {
            for (const Other& mask : other.allowed) allowed.emplace_back(mask);
        }
    };

    // How the step calls a bound check whose type was known when it was bound: `call` invokes
    // the callable that `locate` finds inside its Check (found again whenever the Checks move).
    // The default, for a check bound as a Check, calls the Check.
    struct CheckCall {
        bool (*call)(void* callable, void* data) = [](void* check, void* data) -> bool {
            return (*static_cast<Check*>(check))(data);
        };
        void* (*locate)(Check& owner) = [](Check& owner) -> void* { return &owner; };
    };

    // A bound check as the step polls it, in input order; the unbound ones are left out.
    struct Poll {
        bool (*call)(void* callable, void* data);
        void* callable;
        void* data;
        std::uint32_t bit;                 // input_bit() of the event
        unsigned event;
    };

    // The poll list points into this VM's checks_. Moving a VM moves the vectors' storage, so
    // the pointers stay good; a copy has its own checks_, so a copied list is marked stale and
    // rebuilt by the copy's next step.
    struct Polls {
        std::vector<Poll> list;
        bool stale = false;

        Polls() = default;
        Polls(const Polls&) : stale(true) {}
        Polls(Polls&&) = default;
        Polls& operator=(const Polls&) {
            list.clear();
            stale = true;
            return *this;
        }
        Polls& operator=(Polls&&) = default;
    };

    void store_check(unsigned event, Check check, CheckCall call) {
        require(event);
        refuse_while_polling("bind a check");
        if (image_.controllable.test(event)) {
            throw std::invalid_argument(image_.event_name(event) + " is controllable: it takes an action, not a check");
        }
        checks_[event] = std::move(check);
        check_calls_[event] = checks_[event] ? call : CheckCall();
        rebuild_polls();
    }

    // The poll loop walks polls_.list, whose entries point at the bound checks: a check that
    // rebinds a check or loads an image while the checks are polled would free what the loop
    // is about to call, so that is refused (an action may: the checks have been polled).
    void refuse_while_polling(const char* what) const {
        if (polling_) throw std::logic_error(std::string("a check cannot ") + what + " while the VM polls its checks");
    }

    // The poll list from the bound checks: rebuilt whenever a binding or the image changes, so
    // the step neither walks unbound events nor tests for an empty Check.
    void rebuild_polls() {
        polls_.list.clear();
        polls_.stale = false;
        for (std::size_t i = 0; i < derived_.input_order.size(); ++i) {
            const unsigned e = derived_.input_order[i];
            if (!checks_[e]) continue;
            const CheckCall& how = check_calls_[e];
            polls_.list.push_back(Poll{how.call, how.locate(checks_[e]), data_[e], input_bit(i), e});
        }
        note_actions();
    }

    // acting_ and acting_inputs_ from the bound actions, so that the step tests one set instead
    // of an Action per event. Leaves the poll list alone: a check may set an action.
    void note_actions() {
        acting_ = Mask();
        acting_inputs_ = 0;
        for (unsigned e = 0; e < image_.num_events; ++e) acting_.set_if(e, static_cast<bool>(actions_[e]));
        for (std::size_t i = 0; i < derived_.input_order.size(); ++i) {
            if (acting_.test(derived_.input_order[i])) acting_inputs_ |= input_bit(i);
        }
    }

    // The bit of the i-th input (in input order) in a set of inputs (Composed), 0 without
    // composed states.
    std::uint32_t input_bit(std::size_t i) const {
        return derived_.composed.count != 0 ? std::uint32_t{1} << i : 0;
    }

    // Composed states: the tuples of supervisor states that steps can reach from the initial
    // tuple (the supervisors' synchronous product, with the inputs' violations: a supervisor
    // without a transition on an input stays), numbered breadth first from 0, the initial tuple.
    // Built at load when small (kComposedCells, kFiredLists). A step then gathers the inputs
    // that occur as bits while it polls, moves by all of them with one table entry, takes its
    // choice from one list per composed state, and returns one of the lists of fired events
    // made here (one per set of inputs and choice) instead of building one: a branch per
    // occurring input or per event pushed would be as good as random to a predictor, and
    // mispredicted branches and a chain of dependent loads per input cost the small models'
    // steps more than all the rest.
    static constexpr std::size_t kComposedCells = std::size_t{1} << 14;   // of each table: 64 KB
    static constexpr std::size_t kFiredLists = 1024;                      // sets of inputs x slots
    static constexpr unsigned kNoComposed = 0xFFFF;
    static constexpr unsigned kNoEvent = 255;       // above every event (E <= 255)

    // A composed state's choices: choices[first .. first + count), the first one copied here
    // so that a state with one choice or none takes it with one load less.
    struct Head {
        std::uint32_t choice;
        std::uint32_t first;
        std::uint32_t count;
    };

    struct Composed {
        std::size_t count = 0;                      // composed states; 0: none built
        unsigned inputs = 0;                        // uncontrollable events (bits of a set of inputs)
        std::vector<std::uint32_t> after;           // [c << inputs | set of inputs]: the composed state
                                                    // reached by the inputs, in input order, above the
                                                    // violations they count << 16
        std::vector<std::uint16_t> globals;         // [c * supervisors + s]: s's global state in c
        std::vector<std::uint16_t> locals;          // ... and its own state number
        std::vector<Head> heads;                    // per c: its choices, in event order: the successor
        std::vector<std::uint32_t> choices;         // above the slot << 16 of each of its enabled
                                                    // events, or (none enabled) c above slot 0
        std::vector<Mask> enabled;                  // c's enabled events as a set
        bool draws_vary = false;                    // some composed states draw (two choices or
                                                    // more), others do not (pick_uniform)
        std::vector<unsigned> slot_event;           // per slot: kNoEvent, then the controllable events
        std::vector<std::vector<unsigned>> fired;   // [inputs * slots + slot]: the fired events of a
                                                    // step whose inputs, as bits in input order,
                                                    // and choice are those
        std::vector<std::uint64_t> place;           // per supervisor: its place value in a tuple's key
        std::vector<std::uint64_t> keys;            // the composed states' keys, ascending,
        std::vector<std::uint16_t> key_state;       // ... and the composed state of each
    };

    // Lookup structures derived from an image (and the priority option) once, at load.
    struct Derived {
        std::vector<unsigned> input_order;              // public uncontrollable, then private
        Sets<Mask> wide;
        Sets<BasicMask<1>> narrow;                      // the same for images of up to 64 events
        std::size_t num_globals = 0;                    // global states: all supervisors' states
        std::vector<std::uint32_t> successors;          // per (event, global state): successor_at() or
                                                        // kNoSuccessor (empty above kDenseSlots cells)
        std::vector<unsigned> event_sups;               // the supervisors holding each event, event
        std::vector<unsigned> event_sups_first;         // by event: e's from event_sups_first[e] on
        std::vector<unsigned> rank;                     // per event: rank for policy first
        Composed composed;
    };

    static Derived derive(const Image& image, const Options& options) {
        Derived d;
        const Mask all = Mask::first(image.num_events);
        const Mask uncontrollable = image.controllable.complement_in(all);
        d.wide.controllable = image.controllable;
        d.wide.public_inputs = uncontrollable & image.public_events;
        d.wide.private_inputs = image.public_events.complement_in(uncontrollable);
        d.wide.public_inputs.for_each([&](unsigned e) { d.input_order.push_back(e); });
        d.wide.private_inputs.for_each([&](unsigned e) { d.input_order.push_back(e); });
        // The successor of every state on every event, found once here instead of by a rank
        // count per supervisor and step (a table of states x events; larger images rank).
        d.num_globals = image.state_defined.size();
        const std::size_t cells = d.num_globals * image.num_events;
        if (cells <= kDenseSlots) {
            d.successors.assign(cells, kNoSuccessor);
            for (unsigned s = 0; s < image.num_supervisors; ++s) {
                for (unsigned q = 0; q < image.sup_num_states[s]; ++q) {
                    const std::size_t g = image.sup_first_state[s] + q;
                    unsigned slot = image.state_first[g];
                    image.state_defined[g].for_each([&](unsigned e) {
                        d.successors[e * d.num_globals + g] =
                            successor_at(slot, image.sup_first_state[s] + image.targets[slot]);
                        ++slot;
                    });
                }
            }
        }
        d.wide.allowed.resize(image.state_defined.size());
        for (unsigned s = 0; s < image.num_supervisors; ++s) {
            Mask outside = image.sup_alphabet[s].complement_in(all);
            for (unsigned q = 0; q < image.sup_num_states[s]; ++q) {
                const unsigned g = image.sup_first_state[s] + q;
                d.wide.allowed[g] = image.state_defined[g];
                d.wide.allowed[g] |= outside;
            }
        }
        if (image.num_events <= 64) d.narrow = Sets<BasicMask<1>>(d.wide);
        for (unsigned e = 0; e < image.num_events; ++e) {
            d.event_sups_first.push_back(static_cast<unsigned>(d.event_sups.size()));
            for (unsigned s = 0; s < image.num_supervisors; ++s) {
                if (image.sup_alphabet[s].test(e)) d.event_sups.push_back(s);
            }
        }
        d.event_sups_first.push_back(static_cast<unsigned>(d.event_sups.size()));
        std::vector<unsigned> listed;
        for (const std::string& name : options.priority) listed.push_back(image.event_index(name));
        d.rank.resize(image.num_events);
        for (unsigned e = 0; e < image.num_events; ++e) {
            d.rank[e] = static_cast<unsigned>(listed.size()) + e;
            for (unsigned i = 0; i < listed.size(); ++i) {
                if (listed[i] == e) {
                    d.rank[e] = i;
                    break;
                }
            }
        }
        d.composed = compose(image, d);
        return d;
    }

    // The composed states of an image with a successor table, or none (count 0) when there are
    // more than kComposedCells allows or a tuple's key would not fit 64 bits. Breadth first:
    // every composed state's successors are numbered before the next state is expanded.
    static Composed compose(const Image& image, const Derived& d) {
        const unsigned n_sups = image.num_supervisors, n_events = image.num_events;
        const std::size_t limit = std::min<std::size_t>(kComposedCells / n_events, kNoComposed);
        const std::size_t n_inputs = d.input_order.size();
        Composed out;
        out.slot_event.push_back(kNoEvent);
        image.controllable.for_each([&](unsigned e) { out.slot_event.push_back(e); });
        const std::size_t slots = out.slot_event.size();
        if (n_inputs >= 16 || (std::size_t{1} << n_inputs) * slots > kFiredLists) return Composed();
        std::uint64_t place = 1;
        for (unsigned s = 0; s < n_sups; ++s) {
            if (d.successors.empty() || place > UINT64_MAX / image.sup_num_states[s]) return Composed();
            out.place.push_back(place);
            place *= image.sup_num_states[s];
        }
        std::map<std::uint64_t, std::uint16_t> numbers;   // key -> composed state
        std::vector<std::uint32_t> rows;                  // [c * events + e]: c's successor on e above
                                                          // its violations << 16 (kNoComposed: never taken)
        std::vector<std::uint16_t> tuple(n_sups);
        // The number of the tuple of global states `tuple`, added if new; kNoComposed past the limit.
        const auto number = [&]() -> unsigned {
            std::uint64_t key = 0;
            for (unsigned s = 0; s < n_sups; ++s) key += (tuple[s] - image.sup_first_state[s]) * out.place[s];
            const auto found = numbers.find(key);
            if (found != numbers.end()) return found->second;
            if (numbers.size() == limit) return kNoComposed;
            out.globals.insert(out.globals.end(), tuple.begin(), tuple.end());
            return numbers.emplace(key, static_cast<std::uint16_t>(numbers.size())).first->second;
        };
        for (unsigned s = 0; s < n_sups; ++s) {
            tuple[s] = static_cast<std::uint16_t>(image.sup_first_state[s] + image.sup_initial[s]);
        }
        number();
        for (std::size_t c = 0; c < numbers.size(); ++c) {
            for (unsigned e = 0; e < n_events; ++e) {
                std::copy_n(out.globals.begin() + static_cast<std::ptrdiff_t>(c * n_sups), n_sups, tuple.begin());
                std::uint32_t violations = 0;
                for (unsigned k = d.event_sups_first[e]; k < d.event_sups_first[e + 1]; ++k) {
                    const unsigned s = d.event_sups[k];
                    const std::uint32_t next = d.successors[e * d.num_globals + tuple[s]];
                    if (next == kNoSuccessor) {
                        ++violations;
                    } else {
                        tuple[s] = static_cast<std::uint16_t>(next);
                    }
                }
                if (violations != 0 && image.controllable.test(e)) {   // never chosen here
                    rows.push_back(kNoComposed);
                    continue;
                }
                const unsigned successor = number();
                if (successor == kNoComposed) return Composed();
                rows.push_back(successor | violations << 16);
            }
        }
        out.count = numbers.size();
        out.inputs = static_cast<unsigned>(n_inputs);
        if ((out.count << n_inputs) > kComposedCells) return Composed();
        for (std::size_t c = 0; c < out.count; ++c) {
            const std::uint32_t* const next = &rows[c * n_events];   // c's successors by event
            for (std::uint32_t inputs = 0; inputs < (std::uint32_t{1} << n_inputs); ++inputs) {
                std::uint32_t reached = static_cast<std::uint32_t>(c), violations = 0;
                for (std::size_t i = 0; i < n_inputs; ++i) {
                    if (((inputs >> i) & 1u) == 0) continue;
                    const std::uint32_t entry = rows[reached * n_events + d.input_order[i]];
                    reached = entry & 0xFFFFu;
                    violations += entry >> 16;
                }
                out.after.push_back(reached | violations << 16);
            }
            Mask enabled = image.controllable;
            for (unsigned s = 0; s < n_sups; ++s) {
                const unsigned g = out.globals[c * n_sups + s];
                enabled &= d.wide.allowed[g];
                out.locals.push_back(static_cast<std::uint16_t>(g - image.sup_first_state[s]));
            }
            out.enabled.push_back(enabled);
            const std::uint32_t first = static_cast<std::uint32_t>(out.choices.size());
            for (std::uint32_t slot = 1; slot < slots; ++slot) {
                const unsigned e = out.slot_event[slot];
                if (enabled.test(e)) out.choices.push_back((next[e] & 0xFFFFu) | slot << 16);
            }
            if (!enabled.any()) out.choices.push_back(static_cast<std::uint32_t>(c));
            out.heads.push_back(Head{out.choices[first], first, enabled.count()});
        }
        const auto draws = [](const Head& head) { return head.count > 1; };
        out.draws_vary = std::any_of(out.heads.begin(), out.heads.end(), draws) &&
                         !std::all_of(out.heads.begin(), out.heads.end(), draws);
        for (std::uint32_t inputs = 0; inputs < (std::uint32_t{1} << n_inputs); ++inputs) {
            for (std::size_t slot = 0; slot < slots; ++slot) {
                std::vector<unsigned> fired;
                for (std::size_t i = 0; i < n_inputs; ++i) {
                    if ((inputs >> i) & 1u) fired.push_back(d.input_order[i]);
                }
                if (slot != 0) fired.push_back(out.slot_event[slot]);
                out.fired.push_back(std::move(fired));
            }
        }
        for (const auto& entry : numbers) {
            out.keys.push_back(entry.first);
            out.key_state.push_back(entry.second);
        }
        return out;
    }

    template <class M>
    M enabled_set(const Sets<M>& sets) const {
        M mask = sets.controllable;
        for (unsigned s = 0; s < image_.num_supervisors; ++s) {
            mask &= sets.allowed[globals_[s]];
        }
        return mask;
    }

    // A step: from the composed state (Composed) when the VM is in one, else the general way.
    template <class M>
    const std::vector<unsigned>& step_with(const Sets<M>& sets, M& previous) {
        if (composed_ != kNoComposed) return step_composed(sets, previous);
        return step_general(sets, occurrence(previous));
    }

    // Step 1: calls f(poll, value) for every bound check in input order, with its value.
    template <class F>
    SWARMVM_INLINE void poll(F&& f) {
        if (polls_.stale) rebuild_polls();
        polling_ = true;
        for (const Poll& p : polls_.list) {
            bool value;
            try {
                value = p.call(p.callable, p.data);
            } catch (...) {
                polling_ = false;
                callback_threw(p.event, "check");
            }
            f(p, value);
        }
        polling_ = false;
    }

    // Steps 1 and 2: polls the bound checks and returns the events that occur.
    template <class M>
    M occurrence(M& previous) {
        M current;
        poll([&](const Poll& p, bool value) { current.set_if(p.event, value); });
        fired_.clear();     // after the checks: one that throws leaves the last step's events
        const M occurred = options_.inputs == Inputs::edge ? previous.complement_in(current) : current;
        previous = current;
        return occurred;
    }

    // A step from composed state composed_ (Composed), without a branch on what the checks
    // return: the inputs that occur gather as bits in input order while they are polled, and
    // one table entry gives where they lead. An input with an action, or a violation with a
    // hook to call, hands the step to step_general before anything changed, so that callbacks
    // see the states they would.
    template <class M>
    const std::vector<unsigned>& step_composed(const Sets<M>& sets, M& previous) {
        const Composed& composed = derived_.composed;
        const bool edge = options_.inputs == Inputs::edge;
        M current;   // the checks' values: only edge inputs need them, at the next step
        std::uint32_t inputs = 0;
        poll([&](const Poll& p, bool value) {
            if (edge) current.set_if(p.event, value);
            const std::uint32_t occurs = std::uint32_t{value} & ~std::uint32_t{edge && previous.test(p.event)};
            inputs |= p.bit & (0u - occurs);
        });
        if (edge) previous = current;
        // composed_ is read after the checks, which may have reset the VM or fired an event.
        const bool inside = composed_ != kNoComposed;
        const std::uint32_t after = inside ? composed.after[composed_ << composed.inputs | inputs] : 0;
        const std::uint32_t c = after & 0xFFFFu, violations = after >> 16;
        if (!inside || (inputs & acting_inputs_) != 0 || (on_violation_ && violations != 0)) {
            fired_.clear();
            return step_general(sets, occurred_in<M>(inputs));
        }
        // Saturating, without a branch: violations are as likely as the inputs that cause them.
        const std::uint64_t total = std::uint64_t{violations_} + violations;
        violations_ = static_cast<std::uint32_t>(std::min<std::uint64_t>(total, kMaxViolations));
        const std::vector<unsigned>* const fired = &composed.fired[inputs * composed.slot_event.size()];
        if (options_.control == Control::if_quiet && inputs != 0) return settle(c, fired[0]);
        const Head& head = composed.heads[c];
        std::uint32_t choice = head.choice;
        if (options_.policy == Policy::uniform) {
            if (composed.draws_vary || head.count > 1) {
                choice = composed.choices[head.first + pick_uniform(rng_, head.count, composed.draws_vary)];
            }
        } else if (head.count > 1) {
            settle(c, fired[0]);   // the weighted policy reads the supervisors' states
            choice = composed.choices[head.first + composed.enabled[c].count_below(select_listed(composed.enabled[c]))];
        }
        const unsigned slot = choice >> 16, event = composed.slot_event[slot];
        settle(choice & 0xFFFFu, fired[slot]);
        if (acting_.test(event)) {
            fired_ = fired[slot];   // the action may load another image, and its lists
            act(event);
            return fired_;
        }
        return fired[slot];
    }

    // The events of a set of inputs (Composed), as a set of events.
    template <class M>
    M occurred_in(std::uint32_t inputs) const {
        M occurred;
        for (std::size_t i = 0; i < derived_.input_order.size(); ++i) {
            occurred.set_if(derived_.input_order[i], (inputs & input_bit(i)) != 0);
        }
        return occurred;
    }

    // Makes composed state c the supervisors' states; returns `fired`.
    const std::vector<unsigned>& settle(unsigned c, const std::vector<unsigned>& fired) {
        const Composed& composed = derived_.composed;
        const std::size_t n = states_.size();
        composed_ = c;
        for (std::size_t s = 0; s < n; ++s) {
            globals_[s] = composed.globals[c * n + s];
            states_[s] = composed.locals[c * n + s];
        }
        return fired;
    }

    // Steps 3 to 6 supervisor by supervisor, then the composed state of the outcome (if any).
    // Out of line: rare where composed states exist. composed_ is cleared first, so that an
    // action that throws leaves the next step to find it again. An input's action that loads
    // an image ends the step there: the other inputs are the old image's events, and load()
    // has reset the VM (and found its composed state).
    template <class M>
    SWARMVM_NOINLINE const std::vector<unsigned>& step_general(const Sets<M>& sets, const M& occurred) {
        composed_ = kNoComposed;
        if (!apply_inputs(sets, occurred)) return fired_;
        if (control_continues()) {
            const M mask = enabled_set(sets);
            if (mask.any()) {
                const unsigned choice = select_event(mask);
                fired_.push_back(choice);
                fire(choice);
            }
        }
        relocate();
        return fired_;
    }

    // Step 3: fires the occurring inputs in input order, public ones first, each added to
    // fired_; false when an action loaded an image, which ends the step after its event.
    template <class M>
    bool apply_inputs(const Sets<M>& sets, const M& occurred) {
        const unsigned loads = loads_;
        const auto fire_input = [this, loads](unsigned e) {
            if (loads_ != loads) return;
            fired_.push_back(e);
            fire(e);
        };
        (occurred & sets.public_inputs).for_each(fire_input);
        (occurred & sets.private_inputs).for_each(fire_input);
        return loads_ == loads;
    }

    // Step 4: whether the step goes on to choose (with if-quiet control, not after an input).
    bool control_continues() const { return fired_.empty() || options_.control != Control::if_quiet; }

    // composed_ from the supervisors' states: their composed state, or kNoComposed.
    void relocate() {
        const Composed& composed = derived_.composed;
        composed_ = kNoComposed;
        if (composed.count == 0) return;
        std::uint64_t key = 0;
        for (std::size_t s = 0; s < states_.size(); ++s) key += states_[s] * composed.place[s];
        const auto at = std::lower_bound(composed.keys.begin(), composed.keys.end(), key);
        if (at != composed.keys.end() && *at == key) composed_ = composed.key_state[at - composed.keys.begin()];
    }

    void require(unsigned event) const {
        if (event >= image_.num_events) {
            throw UnknownEvent("event index " + std::to_string(event) + " out of range (0.." +
                               std::to_string(image_.num_events - 1) + ")");
        }
    }

    // Calls f(s) for every supervisor s whose alphabet holds `event`, in supervisor order.
    template <class F>
    void for_each_sup(unsigned event, F&& f) const {
        const unsigned* const sups = derived_.event_sups.data();
        const unsigned* const end = sups + derived_.event_sups_first[event + 1];
        for (const unsigned* s = sups + derived_.event_sups_first[event]; s != end; ++s) f(*s);
    }

    // The successors on event e by global state (images with a successor table).
    const std::uint32_t* successors_of(unsigned e) const {
        return derived_.successors.data() + static_cast<std::size_t>(e) * derived_.num_globals;
    }

    // Supervisor s's successor on e (successor_at()), or kNoSuccessor if undefined.
    std::uint32_t successor(unsigned s, unsigned e) const {
        if (!derived_.successors.empty()) return successors_of(e)[globals_[s]];
        return ranked_successor(s, e);
    }

    // successor() of an image too large for the table: a rank count in the state's defined
    // events.
    std::uint32_t ranked_successor(unsigned s, unsigned e) const {
        const unsigned g = globals_[s];
        const Mask& defined = image_.state_defined[g];
        if (!defined.test(e)) return kNoSuccessor;
        const unsigned slot = image_.state_first[g] + defined.count_below(e);
        return successor_at(slot, image_.sup_first_state[s] + image_.targets[slot]);
    }

    // The transitions of `event` in every supervisor holding it, then its action. The rare
    // paths (an image without a successor table, an action) are calls, so that the loop keeps
    // its pointers in registers.
    SWARMVM_INLINE void fire(unsigned event) {
        if (derived_.successors.empty()) {
            transit_ranked(event);
        } else {
            const std::uint32_t* const table = successors_of(event);
            const std::uint16_t* const globals = globals_.data();
            transit(event, [table, globals](unsigned s) { return table[globals[s]]; });
        }
        if (actions_[event]) act(event);
    }

    // Moves every supervisor holding `event` to successor(s) (successor_at()); a supervisor
    // without one (kNoSuccessor) stays and counts a violation.
    template <class Successor>
    void transit(unsigned event, Successor&& successor) {
        std::uint16_t* const globals = globals_.data();
        std::uint16_t* const states = states_.data();
        const std::uint16_t* const first = image_.sup_first_state.data();
        for_each_sup(event, [&](unsigned s) {
            const std::uint32_t next = successor(s);
            if (next == kNoSuccessor) {
                violate(event, s);
            } else {
                globals[s] = static_cast<std::uint16_t>(next);
                states[s] = static_cast<std::uint16_t>(globals[s] - first[s]);
            }
        });
    }

    SWARMVM_NOINLINE void transit_ranked(unsigned event) {
        transit(event, [this, event](unsigned s) { return ranked_successor(s, event); });
    }

    // The hook may not load an image (load() refuses): transit() is still walking the
    // event's supervisors in the tables a load would free. A hook that throws ends the step
    // there, as CallbackError "violation hook" (docs/targets-cpp-python.md, "Exceptions").
    void violate(unsigned event, unsigned s) {
        if (violations_ != kMaxViolations) ++violations_;
        if (!on_violation_) return;
        in_violation_hook_ = true;
        try {
            on_violation_(event, s);
        } catch (...) {
            in_violation_hook_ = false;
            callback_threw(event, "violation hook");
        }
        in_violation_hook_ = false;
    }

    // An action that loads an image replaces actions_ while one of its elements runs: load()
    // keeps the replaced vectors in retired_actions_ until the outermost action returns.
    SWARMVM_NOINLINE void act(unsigned event) {
        ++running_actions_;
        try {
            actions_[event](data_[event]);
        } catch (...) {
            done_acting();
            callback_threw(event, "action");
        }
        done_acting();
    }

    void done_acting() {
        if (--running_actions_ == 0) retired_actions_.clear();
    }

    // Called in a catch block: the exception in flight nested in a CallbackError naming it.
    [[noreturn]] void callback_threw(unsigned event, const char* kind) const {
        std::string cause = "an exception that is not a std::exception";
        try {
            throw;
        } catch (const std::exception& ex) {
            cause = ex.what();
        } catch (...) {
        }
        std::throw_with_nested(CallbackError(image_.event_name(event), kind, cause));
    }

    std::uint32_t weight(unsigned event) const {
        std::uint32_t w = kQ15One;
        if (!image_.has_probs()) return w;
        for_each_sup(event, [&](unsigned s) {
            w = (w * image_.probs[successor(s, event) >> 16]) >> 15;
        });
        return w;
    }

    template <class M>
    unsigned select_event(const M& mask) {
        if (options_.policy == Policy::uniform) {
            const unsigned n = mask.count();
            return mask.nth(n == 1 ? 0 : scale_below(rng_.next(), n));
        }
        return select_listed(mask);
    }

    // select_event() for the policies that list the enabled events (first, probabilistic): out of
    // line, so that the uniform pick stays a few instructions in the step.
    template <class M>
    SWARMVM_NOINLINE unsigned select_listed(const M& mask) {
        std::array<unsigned, 256> en{};
        unsigned n = 0;
        mask.for_each([&](unsigned e) { en[n++] = e; });
        if (options_.policy == Policy::first) {
            unsigned best = en[0];
            for (unsigned i = 1; i < n; ++i) {
                if (derived_.rank[en[i]] < derived_.rank[best]) best = en[i];
            }
            return best;
        }
        if (n == 1) return en[0];
        std::array<std::uint32_t, 256> w;
        std::uint32_t total = 0;
        for (unsigned i = 0; i < n; ++i) {
            w[i] = weight(en[i]);
            total += w[i];
        }
        if (total == 0) return en[scale_below(rng_.next(), n)];
        std::uint32_t pick = rng_.next() % total;
        for (unsigned i = 0; i < n; ++i) {
            if (pick < w[i]) return en[i];
            pick -= w[i];
        }
        throw std::logic_error("unreachable: pick below total");
    }

    Options options_;
    Rng rng_;
    Image image_;
    Derived derived_;
    std::vector<Action> actions_;
    std::vector<Check> checks_;
    std::vector<CheckCall> check_calls_;   // per event, beside checks_
    Polls polls_;
    bool polling_ = false;            // inside step_with's poll loop (refuse_while_polling)
    bool in_violation_hook_ = false;  // inside on_violation_ (violate)
    unsigned loads_ = 0;              // images loaded: step_general ends the step when it changes
    unsigned running_actions_ = 0;    // actions running (act)
    std::vector<std::vector<Action>> retired_actions_;   // replaced by a load while one runs (act)
    std::vector<void*> data_;
    ViolationHook on_violation_;
    std::vector<std::uint16_t> states_;
    std::vector<std::uint16_t> globals_;   // per supervisor: its state's global index
    unsigned composed_ = kNoComposed;      // the composed state of states_, or kNoComposed
    Mask acting_;                          // the events with an action
    std::uint32_t acting_inputs_ = 0;      // ... among the inputs, as Poll::bit
    Mask previous_;                   // check values of the previous step (edge), for E > 64
    BasicMask<1> previous_narrow_;    // ... for E <= 64
    std::uint32_t violations_ = 0;
    std::vector<unsigned> fired_;
};

using VM = BasicVM<XorShift32>;

// One line of the canonical trace (docs/conformance.md): step, events, states, violations.
inline std::string format_trace_line(unsigned step, const std::vector<std::string>& names,
                                     const std::vector<std::uint16_t>& states, std::uint32_t violations) {
    std::string line = std::to_string(step) + " ";
    if (names.empty()) line += "-";
    for (std::size_t i = 0; i < names.size(); ++i) line += (i ? "," : "") + names[i];
    line += " ";
    for (std::size_t i = 0; i < states.size(); ++i) line += (i ? "," : "") + std::to_string(states[i]);
    return line + " " + std::to_string(violations);
}

// Binds the check of every uncontrollable event to the script row `row` points at (no event
// occurs while it is null): how the conformance harnesses drive a VM from an event script.
// `row` must outlive the bindings.
template <class Rng>
void bind_script_checks(BasicVM<Rng>& vm, const Mask* const& row) {
    for (unsigned e = 0; e < vm.image().num_events; ++e) {
        if (!vm.image().controllable.test(e)) {
            vm.set_check(e, [&row, e](void*) { return row != nullptr && row->test(e); });
        }
    }
}

// Reads an event script in its text form (docs/conformance.md: per step the EV_ names that
// occur, or "-"; blank and '#' lines skipped) as one mask per step. An unknown or
// controllable event throws std::invalid_argument naming the line.
inline std::vector<Mask> read_event_script(const Image& image, std::istream& in) {
    std::vector<Mask> rows;
    std::string line;
    for (unsigned number = 1; std::getline(in, line); ++number) {
        std::istringstream words(line);
        const std::vector<std::string> tokens((std::istream_iterator<std::string>(words)),
                                              std::istream_iterator<std::string>());
        if (tokens.empty() || tokens[0][0] == '#') continue;
        Mask row;
        for (const std::string& token : tokens) {
            if (tokens.size() == 1 && token == "-") break;
            const std::string where = "event script line " + std::to_string(number) + ": ";
            if (token.compare(0, 3, "EV_") != 0) throw std::invalid_argument(where + "unknown event " + token);
            unsigned e = 0;
            try {
                e = image.event_index(token);
            } catch (const UnknownEvent&) {
                throw std::invalid_argument(where + "unknown event " + token);
            }
            if (image.controllable.test(e)) {
                throw std::invalid_argument(where + token + " is controllable: the VM chooses it, a script cannot");
            }
            row.set(e);
        }
        rows.push_back(row);
    }
    return rows;
}

// Runs `vm` from reset on an event script (one mask of occurring events per step) and
// returns the canonical trace lines: the conformance harness, as the Python replay().
template <class Rng>
std::vector<std::string> replay(BasicVM<Rng>& vm, const std::vector<Mask>& rows) {
    const Mask* row = nullptr;
    bind_script_checks(vm, row);
    vm.reset();
    std::vector<std::string> lines;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        row = &rows[i];
        std::vector<std::string> names;
        for (unsigned e : vm.step()) names.push_back(vm.image().event_name(e));
        lines.push_back(format_trace_line(static_cast<unsigned>(i + 1), names, vm.states(), vm.violations()));
    }
    for (unsigned e = 0; e < vm.image().num_events; ++e) {
        if (!vm.image().controllable.test(e)) vm.set_check(e, nullptr);
    }
    return lines;
}

}  // namespace swarmvm

#endif  // SWARMVM_VM_HPP
