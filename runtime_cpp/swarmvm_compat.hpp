// swarmvm C++ compatibility layer (docs/compat.md): the published Nadzoru 2 SCT and SCTPub over
// swarmvm's image, stepping canonically (BasicVM) or exactly as the published VM
// (detail::PublishedStep), with the never-stale image lookup beside a supervisor.yaml and the
// SHA-256 it compares. Not part of the VM (swarmvm_vm.hpp): sct.h and swarmvm.hpp include it.
#ifndef SWARMVM_COMPAT_HPP
#define SWARMVM_COMPAT_HPP

#include <array>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "swarmvm_vm.hpp"

namespace swarmvm {

// The image file for a path given to SCT: a supervisor.yaml path means the supervisor.svm
// that `swarmvm pack` / `swarmvm gen` write beside it (no YAML parser on the robot).
inline std::string image_path_for(const std::string& path) {
    const std::string yaml = ".yaml";
    if (path.size() >= yaml.size() && path.compare(path.size() - yaml.size(), yaml.size(), yaml) == 0) {
        return path.substr(0, path.size() - yaml.size()) + ".svm";
    }
    return path;
}

namespace detail {

// SHA-256 (FIPS 180-4) of a byte string, as 32 raw bytes: what `swarmvm pack` records of the
// supervisor.yaml it read, compared by load_beside. Written here: the runtime has no
// dependencies, and a robot build has no crypto library to lean on.
inline std::string sha256(const std::string& message) {
    static const std::uint32_t k[64] = {
        0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
        0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
        0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
        0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
        0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
        0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
        0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
        0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2};
    std::uint32_t h[8] = {0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
                          0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};
    std::string padded = message + '\x80';
    while (padded.size() % 64 != 56) padded += '\0';
    const std::uint64_t bits = static_cast<std::uint64_t>(message.size()) * 8u;
    for (int i = 7; i >= 0; --i) padded += static_cast<char>((bits >> (8 * i)) & 0xFFu);
    const auto rotr = [](std::uint32_t x, unsigned n) { return (x >> n) | (x << (32 - n)); };
    for (std::size_t block = 0; block < padded.size(); block += 64) {
        std::uint32_t w[64];
        for (unsigned t = 0; t < 16; ++t) {
            w[t] = 0;
            for (unsigned b = 0; b < 4; ++b) w[t] = (w[t] << 8) | static_cast<std::uint8_t>(padded[block + 4 * t + b]);
        }
        for (unsigned t = 16; t < 64; ++t) {
            const std::uint32_t s0 = rotr(w[t - 15], 7) ^ rotr(w[t - 15], 18) ^ (w[t - 15] >> 3);
            const std::uint32_t s1 = rotr(w[t - 2], 17) ^ rotr(w[t - 2], 19) ^ (w[t - 2] >> 10);
            w[t] = w[t - 16] + s0 + w[t - 7] + s1;
        }
        std::uint32_t v[8];
        std::copy(h, h + 8, v);
        for (unsigned t = 0; t < 64; ++t) {
            const std::uint32_t t1 = v[7] + (rotr(v[4], 6) ^ rotr(v[4], 11) ^ rotr(v[4], 25)) +
                                     ((v[4] & v[5]) ^ (~v[4] & v[6])) + k[t] + w[t];
            const std::uint32_t t2 = (rotr(v[0], 2) ^ rotr(v[0], 13) ^ rotr(v[0], 22)) +
                                     ((v[0] & v[1]) ^ (v[0] & v[2]) ^ (v[1] & v[2]));
            std::copy_backward(v, v + 7, v + 8);
            v[4] += t1;
            v[0] = t1 + t2;
        }
        for (unsigned i = 0; i < 8; ++i) h[i] += v[i];
    }
    std::string out;
    for (std::uint32_t word : h) {
        for (int i = 3; i >= 0; --i) out += static_cast<char>((word >> (8 * i)) & 0xFFu);
    }
    return out;
}

}  // namespace detail

// The image for a path given to SCT, never stale: for "x/supervisor.yaml", x/supervisor.svm,
// refused (std::runtime_error, one message naming both files and the command that fixes it)
// when it is missing, or when it records the digest of a supervisor.yaml (`swarmvm pack`) and
// the YAML file beside it now has other bytes. Any other path is read as an image.
inline Image load_beside(const std::string& path) {
    const std::string image_path = image_path_for(path);
    if (image_path == path) return Image::load(path);
    const std::string fix = ": run swarmvm pack " + path + " -o " + image_path;
    // Both files through the runtime's input layer (read_regular_file): a FIFO or a device under
    // either name is refused at once, never waited on.
    std::string raw;
    try {
        raw = read_regular_file(image_path, kMaxImageSize, "table image");
    } catch (const FileError& error) {
        if (error.opened()) throw;
        throw std::runtime_error("cannot read table image " + image_path + " for " + path + fix);
    }
    Image image = Image::parse(reinterpret_cast<const std::uint8_t*>(raw.data()), raw.size());
    if (image.source_digest.empty()) return image;
    std::string bytes;
    try {
        bytes = read_regular_file(path, kMaxSourceFileSize, "supervisor file");
    } catch (const FileError& error) {
        if (error.opened()) throw;
        return image;       // no supervisor.yaml beside the image (a robot carries the image alone)
    }
    if (detail::sha256(bytes) != image.source_digest) {
        throw std::runtime_error(image_path + " is stale: it was packed from another version of " + path + fix);
    }
    return image;
}

// How a compatibility object steps (docs/compat.md): canonical, swarmvm's step (BasicVM);
// exact, the published SCT's (the file's event order, every check before any transition, each
// action after its transition, the k-th enabled controllable event in file order with
// k = rng.next() % n); exact_public_first, the published SCTPub's (public events applied before
// private ones).
enum class Step { canonical, exact, exact_public_first };

namespace detail {

// One event's registration as the published VM keeps it (its Scallback): an action, a check and
// the data pointer both receive, each callable an object and a member function of its class.
// The member functions are kept as one type and converted back to their own by a function made
// for their class when registered: a step calls them directly (no std::function, no allocation).
struct Registration {
    struct Opaque;
    using Method = std::array<unsigned char, sizeof(void (Opaque::*)(void*))>;   // a member function's bytes

    void* object = nullptr;
    Method action_method{};
    Method check_method{};
    void (*act)(const Registration&, void*) = nullptr;
    bool (*check)(const Registration&, void*) = nullptr;
    void* data = nullptr;

    // What one add_callback registers: an action, a check, or both (nullptr for the one not given).
    template <class C, class A, class K>
    static Registration of(C* p, A action, K check, void* data) {
        Registration r;
        if constexpr (!std::is_null_pointer<A>::value) r.set_action(p, action);
        if constexpr (!std::is_null_pointer<K>::value) r.set_check(p, check);
        r.data = data;
        return r;
    }

    template <class C>
    void set_action(C* p, void (C::*method)(void*)) {
        object = p;
        action_method = bytes_of(method);
        act = [](const Registration& r, void* d) {
            (static_cast<C*>(r.object)->*from_bytes<void (C::*)(void*)>(r.action_method))(d);
        };
    }
    template <class C, class R>
    void set_check(C* p, R (C::*method)(void*)) {
        object = p;
        check_method = bytes_of(method);
        check = [](const Registration& r, void* d) {
            return static_cast<bool>((static_cast<C*>(r.object)->*from_bytes<R (C::*)(void*)>(r.check_method))(d));
        };
    }

private:
    template <class M>
    static Method bytes_of(M method) {
        static_assert(sizeof(M) == sizeof(Method), "a member function pointer of another size");
        Method out;
        std::copy_n(reinterpret_cast<const unsigned char*>(&method), sizeof(M), out.data());
        return out;
    }
    template <class M>
    static M from_bytes(const Method& bytes) {
        M method;
        std::copy_n(bytes.data(), sizeof(M), reinterpret_cast<unsigned char*>(&method));
        return method;
    }
};

// The published VM's input buffer: the events whose check was true, applied first in first out.
// It outlives a step as the published queue does: when a callback throws, the events not yet
// applied are applied by the next step, after those its checks add. An event is written whether
// its check was true or not and kept only if it was: the step does not branch on a check's value
// (as good as random to a predictor).
class Pending {
public:
    // Room for `more` events after those pending (it grows only when a callback threw).
    void make_room(std::size_t more) {
        if (events_.size() < end_ + more) events_.resize(end_ + more);
    }
    void push_if(unsigned event, bool occurred) {
        events_[end_] = static_cast<std::uint8_t>(event);
        end_ += occurred;
    }
    bool empty() const { return next_ == end_; }
    // The next event into `event`; false, the buffer emptied, when none is left.
    bool take(unsigned& event) {
        if (next_ == end_) {
            next_ = end_ = 0;
            return false;
        }
        event = events_[next_++];
        return true;
    }

private:
    std::vector<std::uint8_t> events_;
    std::size_t next_ = 0, end_ = 0;
};

// The published SCT's step on tables in the file's event order, derived once from an image with
// the order section. The tables are those of automata: the supervisors, or, when it is small,
// their synchronous product, one automaton whose state is the tuple of theirs (a step then moves
// one state, and a state's enabled controllable events are listed once, at construction). Per
// state: the events it allows (a transition, or not in its supervisor's alphabet) as a set, its
// successor on every event (itself without a transition, as the published search leaves it),
// and how get_current_state_string() prints it. A step is a call per registered check, a few
// table loads and set operations per event applied: no map lookup, no search of the supervisor
// data, no allocation. Callbacks are called directly, so what they throw reaches the caller as
// it is, as with the published VM.
//
// The checks' values gather as bits (bit i: the i-th uncontrollable event in file order), without
// a branch on them. When no event of the step has an action and none is left pending, one
// table entry per automaton gives its state after all of them, applied in the published order
// (`after_`, or `landings_` for one automaton, built when small); otherwise they go through the
// published input buffers.
class PublishedStep {
public:
    PublishedStep() = default;
    PublishedStep(const Image& image, bool public_first) : events_(image.num_events) {
        std::vector<unsigned> canonical(events_);   // file index -> the image's index
        for (unsigned c = 0; c < events_; ++c) canonical[image.order[c]] = c;
        for (unsigned f = 0; f < events_; ++f) {
            const bool controllable = image.controllable.test(canonical[f]);
            controllable_.set_if(f, controllable);
            if (controllable) continue;
            ahead_.set_if(static_cast<unsigned>(inputs_.size()), public_first && image.public_events.test(canonical[f]));
            inputs_.push_back(static_cast<std::uint8_t>(f));
        }
        std::vector<Automaton> automata = supervisors(image, canonical);
        if (automata.size() > 1 && product_fits(automata)) automata = {product(automata)};
        flatten(automata);
        registrations_.resize(events_);
        build_after();
    }

    // What add_callback registers: it replaces the event's action, check and data.
    void set_registration(unsigned event, const Registration& r) {
        registrations_[event] = r;
        acting_ = Mask();
        input_registrations_.clear();
        for (std::size_t i = 0; i < inputs_.size(); ++i) {
            acting_.set_if(static_cast<unsigned>(i), registrations_[inputs_[i]].act != nullptr);
            input_registrations_.push_back(registrations_[inputs_[i]]);
        }
    }

    // One published step: every registered check of an uncontrollable event in file order, the
    // events whose check was true applied in that order (public ones first for SCTPub), then the
    // k-th enabled controllable event, k = rng.next() % n, applied. Inlined here, the step of one
    // automaton with landings_ (most models, their product small): one table entry for the inputs
    // and the state's enabled events, one load for the chosen event's successor; the others' step
    // is run_automata.
    template <class Rng>
    void run(Rng& rng) {
        if (landings_.empty()) {
            run_automata(rng);
            return;
        }
        const BasicMask<1> occurred = poll<BasicMask<1>>();
        std::size_t at;
        if ((occurred.word(0) & acting_.word(0)) == 0 && !backlog_) {
            at = (std::size_t{state_[0]} << inputs_.size()) | occurred.word(0);
        } else {
            apply_buffered(occurred);
            at = std::size_t{state_[0]} << inputs_.size();   // no input: the state itself
        }
        const Landing landing = landings_[at];
        if (landing.count == 0) {
            state_[0] = landing.state;
            return;
        }
        const std::uint32_t k = rng.next();   // drawn even when one is enabled, as published
        const std::uint32_t chosen = landing.first + (landing.count == 1 ? 0u : k % landing.count);
        state_[0] = choice_successors_[chosen];
        act(choice_events_[chosen]);
    }

    // "sup:[4,1,3]": every supervisor's state as the file numbers it, from 1.
    std::string state_string() const {
        std::string out = "sup:[";
        for (std::size_t a = 0; a < state_.size(); ++a) out += (a ? "," : "") + labels_[first_state_[a] + state_[a]];
        return out + "]";
    }

private:
    // One supervisor, or the product of all: a state's successors are successors[state * E + event].
    struct Automaton {
        std::vector<Mask> allowed;                // per state
        std::vector<std::uint16_t> successors;
        std::vector<std::string> labels;          // per state: "4" (the file's number from 1), "4,1,3"
        std::size_t start = 0;
        Mask alphabet;
    };
    // Where a step's inputs lead from a state: the state they reach and its enabled controllable
    // events, choice_events_[first .. first + count) in file order, with the state each leads to
    // in choice_successors_. The next state is then at most two dependent loads from the last
    // (state -> landing -> successor), the chain every step waits on; 8 bytes an entry, so at
    // most 512 KiB (kAfterCells entries) per SCT.
    struct Landing {
        std::uint32_t first;
        std::uint16_t count;
        std::uint16_t state;
    };

    // At most this many uncontrollable events, and this many entries in all, for after_.
    static constexpr unsigned kAfterInputs = 12;
    static constexpr std::size_t kAfterCells = std::size_t{1} << 16;
    // At most this many successor entries (states x events) in a product.
    static constexpr std::size_t kProductCells = std::size_t{1} << 16;

    std::vector<Automaton> supervisors(const Image& image, const std::vector<unsigned>& canonical) const {
        std::vector<Automaton> out(image.num_supervisors);
        for (unsigned s = 0; s < image.num_supervisors; ++s) {
            Automaton& a = out[s];
            // Where the published VM starts: the file's sup_current_state, when the image has it.
            a.start = image.start_states.empty() ? image.sup_initial[s] : image.start_states[s];
            for (unsigned f = 0; f < events_; ++f) a.alphabet.set_if(f, image.sup_alphabet[s].test(canonical[f]));
            for (unsigned q = 0; q < image.sup_num_states[s]; ++q) {
                const unsigned g = image.sup_first_state[s] + q;
                const Mask& defined = image.state_defined[g];
                Mask allowed;
                for (unsigned f = 0; f < events_; ++f) {
                    const unsigned c = canonical[f];
                    const bool moves = a.alphabet.test(f) && defined.test(c);
                    allowed.set_if(f, !a.alphabet.test(f) || moves);
                    a.successors.push_back(moves ? image.targets[image.state_first[g] + defined.count_below(c)]
                                                 : static_cast<std::uint16_t>(q));
                }
                a.allowed.push_back(allowed);
                a.labels.push_back(std::to_string(image.state_order[g] + 1u));
            }
        }
        return out;
    }

    bool product_fits(const std::vector<Automaton>& automata) const {
        std::size_t states = 1;
        for (const Automaton& a : automata) {
            states *= a.allowed.size();
            if (states * std::max(events_, 1u) > kProductCells) return false;
        }
        return inputs_.size() <= kAfterInputs && (states << inputs_.size()) <= kAfterCells;
    }

    // The synchronous product: state sum over a of q_a * stride_a (stride_a: the product of the
    // sizes of the automata after a), every event moving each automaton as it would alone.
    Automaton product(const std::vector<Automaton>& parts) const {
        std::vector<std::size_t> stride(parts.size(), 1);
        for (std::size_t a = parts.size() - 1; a-- > 0;) stride[a] = stride[a + 1] * parts[a + 1].allowed.size();
        const std::size_t states = stride[0] * parts[0].allowed.size();
        Automaton out;
        out.alphabet = Mask::first(events_);
        std::vector<std::size_t> q(parts.size());
        for (std::size_t state = 0; state < states; ++state) {
            Mask allowed = out.alphabet;
            std::string label;
            for (std::size_t a = 0; a < parts.size(); ++a) {
                q[a] = state / stride[a] % parts[a].allowed.size();
                allowed &= parts[a].allowed[q[a]];
                label += (a ? "," : "") + parts[a].labels[q[a]];
            }
            out.allowed.push_back(allowed);
            out.labels.push_back(label);
            for (unsigned f = 0; f < events_; ++f) {
                std::size_t next = 0;
                for (std::size_t a = 0; a < parts.size(); ++a) next += stride[a] * parts[a].successors[q[a] * events_ + f];
                out.successors.push_back(static_cast<std::uint16_t>(next));
            }
        }
        for (std::size_t a = 0; a < parts.size(); ++a) out.start += stride[a] * parts[a].start;
        return out;
    }

    // The automata into the step's flat tables.
    void flatten(const std::vector<Automaton>& automata) {
        for (unsigned f = 0; f < events_; ++f) {
            moves_first_.push_back(static_cast<unsigned>(moves_.size()));
            for (std::size_t a = 0; a < automata.size(); ++a) {
                if (automata[a].alphabet.test(f)) moves_.push_back(static_cast<unsigned>(a));
            }
        }
        moves_first_.push_back(static_cast<unsigned>(moves_.size()));
        for (const Automaton& a : automata) {
            state_.push_back(static_cast<std::uint16_t>(a.start));
            first_state_.push_back(static_cast<unsigned>(allowed_.size()));
            allowed_.insert(allowed_.end(), a.allowed.begin(), a.allowed.end());
            labels_.insert(labels_.end(), a.labels.begin(), a.labels.end());
            successors_.insert(successors_.end(), a.successors.begin(), a.successors.end());
        }
        if (events_ <= 64) {
            narrow_controllable_ = BasicMask<1>(controllable_);
            for (const Mask& allowed : allowed_) narrow_allowed_.emplace_back(allowed);
        }
    }

    // after_[after_first_[a] + (q << inputs | occurred)]: automaton a's state after the
    // uncontrollable events `occurred` (bits as poll() gathers them) from state q, in the
    // published order. With one automaton, landings_ in its place: the same entries, each with the
    // enabled controllable events of the state it holds.
    void build_after() {
        const std::size_t n_inputs = inputs_.size();
        if (n_inputs > kAfterInputs) return;
        std::size_t cells = 0;
        for (std::size_t a = 0; a < state_.size(); ++a) cells += automaton_size(a) << n_inputs;
        if (cells > kAfterCells) return;
        std::vector<unsigned> order;   // input bits in the order of application
        for (int pass = 0; pass < 2; ++pass) {
            for (unsigned i = 0; i < n_inputs; ++i) {
                if (ahead_.test(i) == (pass == 0)) order.push_back(i);
            }
        }
        for (std::size_t a = 0; a < state_.size(); ++a) {
            after_first_.push_back(static_cast<unsigned>(after_.size()));
            for (std::size_t q = 0; q < automaton_size(a); ++q) {
                for (std::uint32_t occurred = 0; occurred < (std::uint32_t{1} << n_inputs); ++occurred) {
                    std::size_t state = q;
                    for (unsigned i : order) {
                        if ((occurred >> i) & 1u) state = successors_[(first_state_[a] + state) * events_ + inputs_[i]];
                    }
                    after_.push_back(static_cast<std::uint16_t>(state));
                }
            }
        }
        if (state_.size() != 1) return;
        std::vector<Landing> choices;   // per state
        for (std::size_t q = 0; q < allowed_.size(); ++q) {
            const Mask enabled = controllable_ & allowed_[q];
            choices.push_back(Landing{static_cast<std::uint32_t>(choice_events_.size()),
                                      static_cast<std::uint16_t>(enabled.count()), static_cast<std::uint16_t>(q)});
            enabled.for_each([&](unsigned f) {
                choice_events_.push_back(static_cast<std::uint8_t>(f));
                choice_successors_.push_back(successors_[q * events_ + f]);
            });
        }
        for (std::uint16_t state : after_) landings_.push_back(choices[state]);
        after_ = {};   // run_automata, its only other reader, does not run with landings_
        after_first_ = {};
    }

    std::size_t automaton_size(std::size_t a) const {
        return (a + 1 < first_state_.size() ? first_state_[a + 1] : allowed_.size()) - first_state_[a];
    }

    // The registered checks in file order; the events whose check was true as bits. When a
    // check throws, those already true wait in the input buffers, as in the published VM.
    template <class M>
    M poll() {
        M occurred;
        try {
            for (std::size_t i = 0; i < input_registrations_.size(); ++i) {
                const Registration& r = input_registrations_[i];
                if (r.check != nullptr) occurred.set_if(static_cast<unsigned>(i), r.check(r, r.data));
            }
        } catch (...) {
            buffer(occurred);
            throw;
        }
        return occurred;
    }

    // The events `occurred` into the input buffers: public ones (SCTPub) in one, the others in
    // the other, each in file order.
    template <class M>
    void buffer(const M& occurred) {
        backlog_ = true;
        const M ahead(ahead_);
        pending_public_.make_room(inputs_.size());
        pending_.make_room(inputs_.size());
        (occurred & ahead).for_each([&](unsigned i) { pending_public_.push_if(inputs_[i], true); });
        ahead.complement_in(occurred).for_each([&](unsigned i) { pending_.push_if(inputs_[i], true); });
    }

    // The step of several automata (or of one too large for landings_).
    template <class Rng>
    SWARMVM_NOINLINE void run_automata(Rng& rng) {
        if (inputs_.size() <= 64) {
            apply_inputs(poll<BasicMask<1>>());
        } else {
            apply_inputs(poll<Mask>());
        }
        if (!narrow_allowed_.empty()) {
            choose(narrow_controllable_, narrow_allowed_, rng);
        } else {
            choose(controllable_, allowed_, rng);
        }
    }

    template <class M>
    void apply_inputs(const M& occurred) {
        if ((occurred & M(acting_)).any() || backlog_ || after_.empty()) {
            apply_buffered(occurred);
            return;
        }
        const std::size_t at = occurred.word(0);
        const unsigned shift = static_cast<unsigned>(inputs_.size());
        for (std::size_t a = 0; a < state_.size(); ++a) state_[a] = after_[after_first_[a] + (state_[a] << shift | at)];
    }

    // The events `occurred` applied one by one through the published input buffers, after any
    // left there by a step that threw.
    template <class M>
    SWARMVM_NOINLINE void apply_buffered(const M& occurred) {
        buffer(occurred);
        unsigned event = 0;
        while (pending_public_.take(event)) fire(event);
        while (pending_.take(event)) fire(event);
        backlog_ = false;
    }

    template <class M, class Rng>
    void choose(const M& controllable, const std::vector<M>& allowed, Rng& rng) {
        M enabled = controllable;
        for (std::size_t a = 0; a < state_.size(); ++a) enabled &= allowed[first_state_[a] + state_[a]];
        const unsigned n = enabled.count();
        if (n != 0) fire(enabled.nth(static_cast<unsigned>(rng.next() % n)));
    }

    void fire(unsigned event) {
        for (unsigned k = moves_first_[event]; k < moves_first_[event + 1]; ++k) {
            const unsigned a = moves_[k];
            state_[a] = successors_[(first_state_[a] + state_[a]) * events_ + event];
        }
        act(event);
    }
    void act(unsigned event) const {
        const Registration& r = registrations_[event];
        if (r.act != nullptr) r.act(r, r.data);
    }

    unsigned events_ = 0;
    std::vector<std::uint8_t> inputs_;          // the uncontrollable events, in file order
    Mask ahead_;                                // bits of inputs_ applied first (SCTPub's public events)
    Mask acting_;                               // bits of inputs_ with an action
    std::vector<std::uint16_t> state_;          // per automaton: its state
    std::vector<unsigned> first_state_;         // per automaton: its first global state
    std::vector<std::string> labels_;           // per global state
    Mask controllable_;
    std::vector<Mask> allowed_;                 // per global state
    BasicMask<1> narrow_controllable_;          // the same for up to 64 events
    std::vector<BasicMask<1>> narrow_allowed_;
    std::vector<unsigned> moves_first_;         // per event: the automata it moves, from moves_first_[e] on
    std::vector<unsigned> moves_;
    std::vector<std::uint16_t> successors_;     // [global state * events_ + event]
    std::vector<unsigned> after_first_;         // per automaton, into after_ (empty: no after_)
    std::vector<std::uint16_t> after_;
    std::vector<Landing> landings_;             // one automaton: as after_ (empty: several, or no after_)
    std::vector<std::uint8_t> choice_events_;
    std::vector<std::uint16_t> choice_successors_;
    std::vector<Registration> registrations_;   // per event
    std::vector<Registration> input_registrations_;   // per bit of inputs_: its event's, in a row for poll()
    Pending pending_public_, pending_;
    bool backlog_ = false;                      // the buffers may hold events (a callback threw)
};

}  // namespace detail

// Nadzoru 2's C++ API (the OpenSwarm ARGoS controllers' SCT), so a published controller
// switches to swarmvm without edits:
//   sct->add_callback(this, "EV_x", &C::cb, NULL, NULL);      // controllable
//   sct->add_callback(this, "EV_y", NULL, &C::check, NULL);   // uncontrollable
//   sct->run_step();
// An exact step is the published VM's (detail::PublishedStep), registration included: each
// add_callback replaces the event's action, check and data, a check on a controllable event is
// kept and never called, and what a callback throws reaches the caller unchanged. The canonical
// step is BasicVM's, whose CallbackError wraps what a callback throws, and which refuses a check
// on a controllable event. Unlike the published VM, an unknown event name throws UnknownEvent in
// both (the published VM exits).
template <class Rng = XorShift32>
class BasicSCT {
public:
    // Exact steps need the image's ORDER section (`swarmvm pack` writes it from a
    // supervisor.yaml); without it they throw std::invalid_argument.
    explicit BasicSCT(const std::string& path, Options options = Options(), Rng rng = Rng(),
                      Step step = Step::canonical)
        : vm_(load_beside(path), std::move(options), std::move(rng)), step_(step) {
        const Image& image = vm_.image();
        if (step_ == Step::canonical) {
            for (unsigned e = 0; e < image.num_events; ++e) events[image.event_name(e)] = e;
            return;
        }
        if (image.order.size() != image.num_events || !image.has_names()) {
            throw std::invalid_argument(path + ": the exact step needs the supervisor file's event order, which this "
                                        "image does not keep: write it with swarmvm pack from the supervisor.yaml");
        }
        published_ = detail::PublishedStep(image, step_ == Step::exact_public_first);
        // The file's names as written ("EV_x", "e9", "go-left"), when the image has them.
        for (unsigned e = 0; e < image.num_events; ++e) {
            events[image.written_names.empty() ? image.event_name(e) : image.written_names[e]] = image.order[e];
        }
    }
    virtual ~BasicSCT() = default;

    // Controllable event: an action, no check (the published controllers pass NULL).
    template <class C>
    void add_callback(C* p, const std::string& event, void (C::*clbk)(void*), void* /*no check*/, void* data) {
        const unsigned e = index(event);
        if (step_ != Step::canonical) {
            published_.set_registration(e, detail::Registration::of(p, clbk, nullptr, data));
            return;
        }
        vm_.bind(e, member(p, clbk), typename BasicVM<Rng>::Check(), data);
        if (!vm_.image().controllable.test(e)) vm_.set_check(e, typename BasicVM<Rng>::Check());
    }
    // Uncontrollable event: a check (returning unsigned char or bool), no action.
    template <class C, class R>
    void add_callback(C* p, const std::string& event, void* /*no action*/, R (C::*ci)(void*), void* data) {
        const unsigned e = index(event);
        if (step_ != Step::canonical) {
            published_.set_registration(e, detail::Registration::of(p, nullptr, ci, data));
            return;
        }
        refuse_check_on_controllable(event, e);
        vm_.bind(e, typename BasicVM<Rng>::Action(), typename BasicVM<Rng>::Check(), data);
        vm_.set_action(e, typename BasicVM<Rng>::Action());
        vm_.set_check(e, [p, ci](void* d) { return static_cast<bool>((p->*ci)(d)); });   // the step's direct call
    }
    // Both a check and an action (e.g. turn LEDs on when an uncontrollable event occurs); for a
    // controllable event the check is never called, as in the published SCT.
    template <class C, class R>
    void add_callback(C* p, const std::string& event, void (C::*clbk)(void*), R (C::*ci)(void*), void* data) {
        const unsigned e = index(event);
        if (step_ != Step::canonical) {
            published_.set_registration(e, detail::Registration::of(p, clbk, ci, data));
            return;
        }
        vm_.bind(e, member(p, clbk), typename BasicVM<Rng>::Check(), data);
        if (!vm_.image().controllable.test(e)) vm_.set_check(e, [p, ci](void* d) { return static_cast<bool>((p->*ci)(d)); });
    }

    virtual void run_step() {
        if (step_ == Step::canonical) {
            step_canonical();
        } else {
            published_.run(vm_.rng());
        }
    }

    // Every supervisor's state in supervisor order: canonically "3,0,2"; in an exact step the
    // published string, the file's state numbers from 1: "sup:[4,1,3]".
    virtual std::string get_current_state_string() {
        if (step_ != Step::canonical) return published_.state_string();
        std::string out;
        for (std::size_t s = 0; s < vm_.states().size(); ++s) out += (s ? "," : "") + std::to_string(vm_.states()[s]);
        return out;
    }

    // The canonical VM: it steps in canonical mode; an exact step keeps its own states and
    // callbacks and uses only its image and generator.
    BasicVM<Rng>& vm() { return vm_; }

    // Event name ("EV_x") -> index (the file's in an exact step, else the image's), as the
    // published SCT's public map.
    std::map<std::string, std::size_t> events;

protected:
    unsigned index(const std::string& event) const {
        auto found = events.find(event);
        if (found == events.end()) throw UnknownEvent("no event named '" + event + "' in this supervisor");
        return static_cast<unsigned>(found->second);
    }

    // Canonical mode is stricter than the published VM, which keeps such a check and never
    // calls it: the exact step (sct.h) does the same.
    void refuse_check_on_controllable(const std::string& event, unsigned e) const {
        if (vm_.image().controllable.test(e)) {
            throw std::invalid_argument(event + " is controllable: the canonical SCT takes no check on it (the exact "
                                        "step, as published, keeps it and never calls it)");
        }
    }

    // Out of line, so that run_step, with the exact step inlined, saves fewer registers.
    SWARMVM_NOINLINE void step_canonical() { vm_.step(); }

    BasicVM<Rng> vm_;
    Step step_;
    detail::PublishedStep published_;   // the exact step's tables and states (empty in canonical mode)
};

// The published SCTPub processes public events before private ones; in swarmvm's canonical
// step that order is the semantics of every step, so canonically SCTPub is SCT.
template <class Rng = XorShift32>
class BasicSCTPub : public BasicSCT<Rng> {
public:
    using BasicSCT<Rng>::BasicSCT;
};

using SCT = BasicSCT<XorShift32>;
using SCTPub = BasicSCTPub<XorShift32>;

}  // namespace swarmvm

#endif  // SWARMVM_COMPAT_HPP
