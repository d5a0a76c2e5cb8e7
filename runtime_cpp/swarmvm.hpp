// swarmvm C++ VM: evolves compiled supervisors from a swarmvm table image.
//
// Header only, C++17, standard library only. It implements docs/semantics.md exactly and is
// checked trace for trace against the Python reference (runtime_py/swarmvm_vm.py), whose
// names it mirrors: Image::parse, BasicVM::step, XorShift32, replay, format_trace_line, SCT.
// The tables always come from a table image (docs/image-format.md): compiled in as a byte
// array or read from a .svm file, both go through Image::parse and its checks, so "compiled
// in" and "loaded" are one code path.
#ifndef SWARMVM_HPP
#define SWARMVM_HPP

#include <array>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <fstream>
#include <functional>
#include <iterator>
#include <istream>
#include <algorithm>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

// Keeps a rare path out of a hot loop (GCC and Clang; elsewhere the compiler decides).
#if defined(__GNUC__) || defined(__clang__)
#define SWARMVM_NOINLINE __attribute__((noinline))
#define SWARMVM_INLINE __attribute__((always_inline)) inline
#else
#define SWARMVM_NOINLINE
#define SWARMVM_INLINE inline
#endif

namespace swarmvm {

// The table image format (docs/image-format.md), defined once in runtime_py/swarmvm_format.py;
// tests/image/test_format_constants.py checks these against it. Generated image headers refuse
// to compile against a runtime of another version.
constexpr std::uint8_t kFormatVersion = 1;
constexpr std::uint32_t kMagic = 0x494D5653u;   // "SVMI", as a little-endian u32
constexpr std::size_t kHeaderSize = 16;
constexpr std::size_t kCrcSize = 2;
constexpr std::size_t kMinImageSize = 18;       // header and checksum
constexpr std::size_t kMaxImageSize = 65535;    // the length field is a u16
constexpr std::size_t kAtMagic = 0;             // offsets of the header's fields
constexpr std::size_t kAtVersion = 4;
constexpr std::size_t kAtFlags = 5;
constexpr std::size_t kAtNumEvents = 6;
constexpr std::size_t kAtNumSupervisors = 7;
constexpr std::size_t kAtNumStates = 8;          // u16
constexpr std::size_t kAtNumTransitions = 10;    // u16
constexpr std::size_t kAtStateWidth = 12;
constexpr std::size_t kAtMaskBytes = 13;
constexpr std::size_t kAtLength = 14;            // u16 L, checksum included
constexpr std::uint8_t kFlagNames = 0x01;
constexpr std::uint8_t kFlagProbs = 0x02;
constexpr std::uint8_t kFlagOrder = 0x04;        // source-file event indices (compatibility layers)
constexpr std::uint8_t kFlagSource = 0x08;       // the file's digest, start states, names as written
constexpr std::uint8_t kKnownFlags = 0x0F;       // an image with any other flag bit is refused
constexpr std::uint32_t kQ15One = 32768;
constexpr std::uint32_t kZeroSeed = 0x9E3779B9u;
// The violation counter stops here on every runtime (docs/semantics.md).
constexpr std::uint32_t kMaxViolations = 0xFFFFFFFFu;

// CRC-16/MCRF4XX (reflected polynomial 0x8408, initial 0xFFFF, no final xor): what the
// Kilobot's avr-libc computes with _crc_ccitt_update, so every runtime checks the same sum. A
// byte at a time, branch-free (the byte-wise form of the polynomial, as swarmvm.c computes it).
inline std::uint16_t crc16(const std::uint8_t* data, std::size_t size, std::uint16_t crc = 0xFFFF) {
    for (std::size_t i = 0; i < size; ++i) {
        auto d = static_cast<std::uint8_t>(data[i] ^ static_cast<std::uint8_t>(crc));
        d = static_cast<std::uint8_t>(d ^ static_cast<std::uint8_t>(d << 4));
        crc = static_cast<std::uint16_t>(((static_cast<unsigned>(d) << 8) | (crc >> 8)) ^ (d >> 4) ^
                                         (static_cast<unsigned>(d) << 3));
    }
    return crc;
}

// Why an image is refused: the numbers of swarmvm.h's SVM_ERR_* (runtime_py/swarmvm_format.py
// ErrorCode), so every runtime gives the same code for the same bad image.
enum class ErrorCode : int {
    length = 1,   // shorter than kMinImageSize, longer than kMaxImageSize, or L != the length
    magic = 2,    // not "SVMI"
    version = 3,  // a format version this VM does not read
    crc = 4,      // checksum mismatch
    layout = 5    // header inconsistent, sections do not end at L-2, an index, mask bit or name out of range
};

// A table image that cannot be run; code() says why, what() says where.
class ImageError : public std::runtime_error {
public:
    ImageError(ErrorCode code, const std::string& what) : std::runtime_error(what), code_(code) {}
    ErrorCode code() const { return code_; }

private:
    ErrorCode code_;
};

// A callback registered under a name the supervisor does not have (never mapped to event 0).
class UnknownEvent : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

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

// A set of events, bit e for event e, in Words 64-bit words (events 0 .. 64 Words - 1). Fixed
// size so that the per-step operations are a few word operations the compiler unrolls: Mask
// holds any image's events (E <= 255); the step uses BasicMask<1> for images of up to 64.
template <unsigned Words>
class BasicMask {
public:
    static constexpr unsigned kWords = Words;

    BasicMask() = default;
    // The events of `other` below 64 Words (the others must not matter).
    template <unsigned Other>
    explicit BasicMask(const BasicMask<Other>& other) {
        for (unsigned i = 0; i < kWords && i < Other; ++i) words_[i] = other.word(i);
    }

    std::uint64_t word(unsigned i) const { return words_[i]; }
    bool test(unsigned e) const { return (words_[e >> 6] >> (e & 63u)) & 1u; }
    void set(unsigned e) { words_[e >> 6] |= std::uint64_t{1} << (e & 63u); }
    // set(e) if `on`, without a branch (a check's result is as good as random to a predictor).
    void set_if(unsigned e, bool on) { words_[e >> 6] |= std::uint64_t{on} << (e & 63u); }
    bool any() const {
        std::uint64_t any = 0;
        for (unsigned i = 0; i < kWords; ++i) any |= words_[i];
        return any != 0;
    }
    BasicMask& operator&=(const BasicMask& other) {
        for (unsigned i = 0; i < kWords; ++i) words_[i] &= other.words_[i];
        return *this;
    }
    BasicMask& operator|=(const BasicMask& other) {
        for (unsigned i = 0; i < kWords; ++i) words_[i] |= other.words_[i];
        return *this;
    }
    // The events of `universe` that are not in this set.
    BasicMask complement_in(const BasicMask& universe) const {
        BasicMask out;
        for (unsigned i = 0; i < kWords; ++i) out.words_[i] = universe.words_[i] & ~words_[i];
        return out;
    }
    // Number of events below e in this set: the rank of e's successor in a state's targets.
    unsigned count_below(unsigned e) const {
        unsigned count = 0;
        for (unsigned i = 0; i < (e >> 6); ++i) count += popcount(words_[i]);
        const std::uint64_t low = (std::uint64_t{1} << (e & 63u)) - 1u;
        return count + popcount(words_[e >> 6] & low);
    }
    // Number of events in the set.
    unsigned count() const {
        unsigned n = 0;
        for (unsigned i = 0; i < kWords; ++i) n += popcount(words_[i]);
        return n;
    }
    // The n-th event of the set (n from 0, lowest first); the set has more than n.
    unsigned nth(unsigned n) const {
        unsigned i = 0;
        for (unsigned ones; n >= (ones = popcount(words_[i])); ++i) n -= ones;
        std::uint64_t word = words_[i];
        for (; n != 0; --n) word &= word - 1u;
        return i * 64u + lowest_bit(word);
    }
    // Calls f(e) for every event in the set, lowest first (canonical event order).
    template <class F>
    void for_each(F&& f) const {
        for (unsigned i = 0; i < kWords; ++i) {
            std::uint64_t word = words_[i];
            while (word != 0) {
                f(i * 64u + lowest_bit(word));
                word &= word - 1u;
            }
        }
    }
    // Reads `size` little-endian bytes, bit e%8 of byte e/8 standing for event e.
    static BasicMask from_bytes(const std::uint8_t* data, std::size_t size) {
        BasicMask out;
        for (std::size_t i = 0; i < size; ++i) {
            out.words_[i >> 3] |= std::uint64_t{data[i]} << ((i & 7u) * 8u);
        }
        return out;
    }
    static BasicMask first(unsigned count) {
        BasicMask out;
        for (unsigned e = 0; e < count; ++e) out.set(e);
        return out;
    }
    friend BasicMask operator&(BasicMask a, const BasicMask& b) { return a &= b; }
    friend bool operator==(const BasicMask& a, const BasicMask& b) { return a.words_ == b.words_; }

private:
    // Branch-free bit count, inlined (GCC's builtin becomes a libgcc call without -mpopcnt).
    static unsigned popcount(std::uint64_t x) {
        x = x - ((x >> 1) & 0x5555555555555555u);
        x = (x & 0x3333333333333333u) + ((x >> 2) & 0x3333333333333333u);
        x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0Fu;
        return static_cast<unsigned>((x * 0x0101010101010101u) >> 56);
    }
    static unsigned lowest_bit(std::uint64_t x) {
#if defined(__GNUC__) || defined(__clang__)
        return static_cast<unsigned>(__builtin_ctzll(x));
#else
        unsigned n = 0;
        for (; (x & 1u) == 0; x >>= 1) ++n;
        return n;
#endif
    }

    std::array<std::uint64_t, kWords> words_{};
};

using Mask = BasicMask<4>;

// A parsed table image: the canonical tables every runtime interprets. Events are numbered
// 0..E-1 in canonical (name) order; targets[state_first[g] + rank] is the successor of global
// state g on the event whose bit is the rank-th set bit of state_defined[g].
struct Image {
    std::vector<std::uint8_t> raw;
    unsigned num_events = 0;
    unsigned num_supervisors = 0;
    Mask controllable;
    Mask public_events;
    std::vector<Mask> sup_alphabet;
    std::vector<std::uint16_t> sup_first_state, sup_num_states, sup_initial;
    std::vector<Mask> state_defined;
    std::vector<std::uint16_t> state_first;
    std::vector<std::uint16_t> targets;
    std::vector<std::uint16_t> probs;   // empty without the PROBS section
    std::vector<std::string> names;     // empty without the NAMES section
    std::vector<std::uint8_t> order;          // ORDER section: source-file index of each event
    std::vector<std::uint16_t> state_order;   // ... and source-file number of each state
    // SOURCE section (`swarmvm pack` from a supervisor.yaml): the SHA-256 of the file's bytes
    // (32 raw bytes; empty without the section), each supervisor's start state (the file's
    // sup_current_state, canonically numbered) and each event's name as the file writes it.
    std::string source_digest;
    std::vector<std::uint16_t> start_states;
    std::vector<std::string> written_names;

    bool has_probs() const { return !probs.empty(); }
    bool has_names() const { return !names.empty(); }

    // Checks and decodes an image; throws ImageError naming the first defect.
    static Image parse(const std::uint8_t* data, std::size_t size);

    // Reads a .svm file (at most kMaxImageSize + 1 bytes: a huge or endless file is refused
    // without reading it all) and parses it. std::runtime_error when the file cannot be read.
    static Image load(const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        if (!in) throw std::runtime_error("cannot read table image " + path);
        std::vector<char> bytes(kMaxImageSize + 1);
        in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        bytes.resize(static_cast<std::size_t>(in.gcount()));
        return parse(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    }

    // "EV_<name>" when the image carries names, else "EV_<index>".
    std::string event_name(unsigned event) const {
        return "EV_" + (has_names() ? names[event] : std::to_string(event));
    }

    // Index of an event given as "EV_x" or "x"; UnknownEvent (with the name) otherwise.
    unsigned event_index(const std::string& name) const {
        if (!has_names()) throw UnknownEvent("this image carries no event names: bind " + name + " by index");
        const std::string bare = name.compare(0, 3, "EV_") == 0 ? name.substr(3) : name;
        for (unsigned e = 0; e < num_events; ++e) {
            if (names[e] == bare) return e;
        }
        throw UnknownEvent("no event named '" + name + "' in this supervisor");
    }
};

namespace detail {

// Bounds-checked little-endian reader over the image bytes: a malformed image is refused
// with ImageError, never read past its end.
class Reader {
public:
    Reader(const std::uint8_t* data, std::size_t end) : data_(data), end_(end) {}
    std::size_t pos() const { return pos_; }
    const std::uint8_t* take(std::size_t count) {
        if (count > end_ - pos_) throw ImageError(ErrorCode::layout, "image truncated: a section runs past the checksum");
        const std::uint8_t* at = data_ + pos_;
        pos_ += count;
        return at;
    }
    std::uint8_t u8() { return *take(1); }
    std::uint16_t u16() {
        const std::uint8_t* at = take(2);
        return static_cast<std::uint16_t>(at[0] | (at[1] << 8));
    }
    Mask mask(std::size_t bytes) { return Mask::from_bytes(take(bytes), bytes); }
    void seek(std::size_t pos) { pos_ = pos; }

private:
    const std::uint8_t* data_;
    std::size_t end_;
    std::size_t pos_ = 0;
};

inline std::string hex4(unsigned value) {
    static const char digits[] = "0123456789abcdef";
    std::string out = "0x0000";
    for (int i = 0; i < 4; ++i) out[5 - i] = digits[(value >> (4 * i)) & 15u];
    return out;
}

}  // namespace detail

namespace detail {

inline unsigned u16_at(const std::uint8_t* data, std::size_t at) {
    return static_cast<unsigned>(data[at] | (data[at + 1] << 8));
}

inline ImageError layout_error(const std::string& what) { return ImageError(ErrorCode::layout, "image " + what); }

// Letters, digits and '_': the characters an event name may hold (the input languages' rule).
inline bool name_char(std::uint8_t c) {
    return (c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
}

// The header checks before the layout, in the order of every runtime: length, magic,
// version, checksum.
inline void check_header(const std::uint8_t* data, std::size_t size) {
    if (size < kMinImageSize) {
        throw ImageError(ErrorCode::length, "image truncated: " + std::to_string(size) +
                                                " bytes, the header alone needs " + std::to_string(kMinImageSize));
    }
    if (size > kMaxImageSize) {
        throw ImageError(ErrorCode::length, "image of " + std::to_string(size) +
                                                " bytes or more, over the format's maximum of " +
                                                std::to_string(kMaxImageSize));
    }
    const std::size_t length = u16_at(data, kAtLength);
    if (length != size) {
        throw ImageError(ErrorCode::length,
                         "image length field says " + std::to_string(length) + " bytes, got " + std::to_string(size));
    }
    if (u16_at(data, kAtMagic) != (kMagic & 0xFFFFu) || u16_at(data, kAtMagic + 2) != (kMagic >> 16)) {
        throw ImageError(ErrorCode::magic, "not a swarmvm table image (bad magic, expected SVMI)");
    }
    if (data[kAtVersion] != kFormatVersion) {
        throw ImageError(ErrorCode::version, "image format version " + std::to_string(data[kAtVersion]) +
                                                 ", this VM reads version " + std::to_string(kFormatVersion));
    }
    const unsigned stored = u16_at(data, length - kCrcSize);
    const unsigned computed = crc16(data, length - kCrcSize);
    if (stored != computed) {
        throw ImageError(ErrorCode::crc,
                         "image checksum mismatch (stored " + hex4(stored) + ", computed " + hex4(computed) + ")");
    }
}

// Whether the name whose length byte is at `name` equals one of the names from `first` (the
// section's start) up to it: the compiler writes each event's name once.
inline bool name_repeats(const std::uint8_t* first, const std::uint8_t* name) {
    for (; first != name; first += 1 + first[0]) {
        if (first[0] == name[0] && std::equal(first + 1, first + 1 + first[0], name + 1)) return true;
    }
    return false;
}

// The sections end exactly at the checksum, every name holds name characters only and is given
// once, the order section's event indices are each event once (ErrorCode::layout otherwise).
inline void check_sections(const std::uint8_t* data, std::size_t end) {
    const unsigned m = data[kAtMaskBytes], n_events = data[kAtNumEvents];
    const std::uint8_t flags = data[kAtFlags];
    std::size_t pos = kHeaderSize + 2 * m + data[kAtNumSupervisors] * (m + 6) + u16_at(data, kAtNumStates) * (m + 2) +
                      u16_at(data, kAtNumTransitions) * data[kAtStateWidth];
    if (flags & kFlagProbs) pos += 2 * u16_at(data, kAtNumTransitions);
    if (pos > end) {
        throw layout_error("sections end at byte " + std::to_string(pos) + ", past the checksum at byte " +
                           std::to_string(end));
    }
    if (flags & kFlagNames) {
        const std::size_t names_at = pos;
        for (unsigned e = 0; e < n_events; ++e) {
            if (pos >= end) throw layout_error("names section ends at event " + std::to_string(e));
            const std::size_t name_end = pos + 1 + data[pos];
            if (name_end > end) throw layout_error("event " + std::to_string(e) + "'s name runs past the checksum");
            if (name_repeats(data + names_at, data + pos)) {
                throw layout_error("event " + std::to_string(e) + "'s name is an earlier event's: each is given once");
            }
            for (++pos; pos < name_end; ++pos) {
                if (!name_char(data[pos])) {
                    throw layout_error("event " + std::to_string(e) +
                                       "'s name holds characters other than letters, digits and '_'");
                }
            }
        }
    }
    if (flags & kFlagOrder) {
        const std::size_t n_states = u16_at(data, kAtNumStates);
        if (pos + n_events + 2 * n_states > end) throw layout_error("order section runs past the checksum");
        std::vector<bool> seen(n_events);
        for (unsigned e = 0; e < n_events; ++e, ++pos) {
            if (data[pos] >= n_events) throw layout_error("order section names an event index beyond the events");
            if (seen[data[pos]]) throw layout_error("order section names an event index twice: not a permutation");
            seen[data[pos]] = true;
        }
        pos += 2 * n_states;
    }
    if (flags & kFlagSource) {     // bounds only, as every reader (the compatibility layers use it)
        const std::size_t n_sups = data[kAtNumSupervisors];
        if (pos + 32 + 2 * n_sups > end) throw layout_error("source section runs past the checksum");
        pos += 32 + 2 * n_sups;
        for (unsigned e = 0; e < n_events; ++e) {
            if (pos >= end || pos + 1 + data[pos] > end) {
                throw layout_error("source section: event " + std::to_string(e) + "'s written name runs past the checksum");
            }
            pos += 1 + data[pos];
        }
    }
    if (pos != end) {
        throw layout_error("sections end at byte " + std::to_string(pos) + ", the checksum is at byte " +
                           std::to_string(end));
    }
}

}  // namespace detail

inline Image Image::parse(const std::uint8_t* data, std::size_t size) {
    detail::check_header(data, size);
    const std::uint8_t flags = data[kAtFlags];
    const unsigned n_events = data[kAtNumEvents];
    const unsigned n_sups = data[kAtNumSupervisors];
    const unsigned n_states = detail::u16_at(data, kAtNumStates);
    const unsigned n_trans = detail::u16_at(data, kAtNumTransitions);
    const unsigned width = data[kAtStateWidth];
    const unsigned mask_bytes = data[kAtMaskBytes];
    // (The order section comes only with the names: the compiler writes it with them.)
    if ((width != 1 && width != 2) || mask_bytes != (n_events + 7) / 8 || n_events == 0 || n_sups == 0 ||
        (flags & ~kKnownFlags) != 0 || (flags & (kFlagOrder | kFlagNames)) == kFlagOrder ||
        (flags & (kFlagSource | kFlagOrder)) == kFlagSource) {
        throw detail::layout_error("header inconsistent (events " + std::to_string(n_events) + ", mask bytes " +
                                   std::to_string(mask_bytes) + ", state width " + std::to_string(width) +
                                   ", supervisors " + std::to_string(n_sups) + ", flags " + detail::hex4(flags) + ")");
    }
    const std::size_t end = size - kCrcSize;
    detail::check_sections(data, end);
    Image image;
    image.raw.assign(data, data + size);
    image.num_events = n_events;
    image.num_supervisors = n_sups;
    detail::Reader in(data, end);
    in.seek(kHeaderSize);
    image.controllable = in.mask(mask_bytes);
    image.public_events = in.mask(mask_bytes);
    for (unsigned s = 0; s < n_sups; ++s) {
        image.sup_alphabet.push_back(in.mask(mask_bytes));
        image.sup_first_state.push_back(in.u16());
        image.sup_num_states.push_back(in.u16());
        image.sup_initial.push_back(in.u16());
    }
    for (unsigned g = 0; g < n_states; ++g) {
        image.state_defined.push_back(in.mask(mask_bytes));
        image.state_first.push_back(in.u16());
    }
    for (unsigned t = 0; t < n_trans; ++t) {
        image.targets.push_back(width == 1 ? in.u8() : in.u16());
    }
    if (flags & kFlagProbs) {
        for (unsigned t = 0; t < n_trans; ++t) image.probs.push_back(in.u16());
    }
    if (flags & kFlagNames) {
        for (unsigned e = 0; e < n_events; ++e) {
            const std::uint8_t len = in.u8();
            const std::uint8_t* at = in.take(len);
            image.names.emplace_back(reinterpret_cast<const char*>(at), len);
        }
    }
    if (flags & kFlagOrder) {
        for (unsigned e = 0; e < n_events; ++e) image.order.push_back(in.u8());
        for (unsigned g = 0; g < n_states; ++g) image.state_order.push_back(in.u16());
    }
    if (flags & kFlagSource) {
        const std::uint8_t* digest = in.take(32);
        image.source_digest.assign(reinterpret_cast<const char*>(digest), 32);
        for (unsigned s = 0; s < n_sups; ++s) image.start_states.push_back(in.u16());
        for (unsigned e = 0; e < n_events; ++e) {
            const std::uint8_t len = in.u8();
            const std::uint8_t* at = in.take(len);
            image.written_names.emplace_back(reinterpret_cast<const char*>(at), len);
        }
    }
    // Cross-references: the step indexes with them, so an inconsistent image is refused here.
    const Mask events = Mask::first(n_events);
    const auto beyond_events = [&](const Mask& mask) { return events.complement_in(mask).any(); };
    if (beyond_events(image.controllable) || beyond_events(image.public_events)) {
        throw detail::layout_error("event masks name events beyond the " + std::to_string(n_events) + " events");
    }
    // Besides the indices, what the compiler always writes: each supervisor starts in its state 0,
    // a state has transitions only on its supervisor's events, each state's successors follow the
    // previous state's and the last ends at the last target (no target read twice or never).
    unsigned expected_first = 0, expected_succ = 0;
    for (unsigned s = 0; s < n_sups; ++s) {
        const unsigned first = image.sup_first_state[s], count = image.sup_num_states[s];
        if (first != expected_first || count == 0 || count > n_states - first || image.sup_initial[s] != 0) {
            throw detail::layout_error("supervisor " + std::to_string(s) +
                                       "'s states do not follow the previous supervisor's inside the state section "
                                       "from its initial state 0");
        }
        if (beyond_events(image.sup_alphabet[s])) {
            throw detail::layout_error("supervisor " + std::to_string(s) + "'s alphabet names events beyond the " +
                                       std::to_string(n_events) + " events");
        }
        for (unsigned g = first; g < first + count; ++g) {
            if (beyond_events(image.state_defined[g])) {
                throw detail::layout_error("state " + std::to_string(g) + " has transitions on events beyond the " +
                                           std::to_string(n_events) + " events");
            }
            if (image.sup_alphabet[s].complement_in(image.state_defined[g]).any()) {
                throw detail::layout_error("state " + std::to_string(g) + " has transitions on events outside its "
                                           "supervisor's alphabet");
            }
            if (image.state_first[g] != expected_succ) {
                throw detail::layout_error("state " + std::to_string(g) + "'s successors do not follow the previous "
                                           "state's");
            }
            unsigned successors = 0;
            image.state_defined[g].for_each([&](unsigned) { ++successors; });
            expected_succ += successors;
            if (image.state_first[g] + successors > n_trans) {
                throw detail::layout_error("state " + std::to_string(g) + " has successors outside the target section");
            }
            for (unsigned t = image.state_first[g]; t < image.state_first[g] + successors; ++t) {
                if (image.targets[t] >= count) {
                    throw detail::layout_error("transition " + std::to_string(t) + " leads outside its supervisor");
                }
            }
        }
        expected_first = first + count;
    }
    if (expected_first != n_states) {
        throw detail::layout_error("supervisors hold " + std::to_string(expected_first) + " states, the header says " +
                                   std::to_string(n_states));
    }
    if (expected_succ != n_trans) {
        throw detail::layout_error("states have " + std::to_string(expected_succ) + " successors, the header says " +
                                   std::to_string(n_trans) + " transitions");
    }
    return image;
}

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
    Mask enabled_mask() const { return enabled_in(derived_.wide); }

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
    M enabled_in(const Sets<M>& sets) const {
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
        return step_general(sets, take_inputs(previous));
    }

    // Step 1: calls f(poll, value) for every bound check in input order, with its value.
    template <class F>
    SWARMVM_INLINE void poll_each(F&& f) {
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
    M take_inputs(M& previous) {
        M current;
        poll_each([&](const Poll& p, bool value) { current.set_if(p.event, value); });
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
        poll_each([&](const Poll& p, bool value) {
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
        const unsigned loads = loads_;
        const auto fire_input = [this, loads](unsigned e) {
            if (loads_ != loads) return;
            fired_.push_back(e);
            apply(e);
        };
        (occurred & sets.public_inputs).for_each(fire_input);     // input order: public first
        (occurred & sets.private_inputs).for_each(fire_input);
        if (loads_ != loads) return fired_;
        if (fired_.empty() || options_.control != Control::if_quiet) {
            const M mask = enabled_in(sets);
            if (mask.any()) {
                const unsigned choice = select(mask);
                fired_.push_back(choice);
                apply(choice);
            }
        }
        relocate();
        return fired_;
    }

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
    SWARMVM_INLINE void apply(unsigned event) {
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
                violated(event, s);
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
    void violated(unsigned event, unsigned s) {
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
    unsigned select(const M& mask) {
        if (options_.policy == Policy::uniform) {
            const unsigned n = mask.count();
            return mask.nth(n == 1 ? 0 : scale_below(rng_.next(), n));
        }
        return select_listed(mask);
    }

    // select() for the policies that list the enabled events (first, probabilistic): out of
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
    bool in_violation_hook_ = false;  // inside on_violation_ (violated)
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
    if (!std::ifstream(image_path, std::ios::binary)) {
        throw std::runtime_error("cannot read table image " + image_path + " for " + path + fix);
    }
    Image image = Image::load(image_path);
    std::ifstream yaml(path, std::ios::binary);
    if (!image.source_digest.empty() && yaml) {
        const std::string bytes((std::istreambuf_iterator<char>(yaml)), std::istreambuf_iterator<char>());
        if (detail::sha256(bytes) != image.source_digest) {
            throw std::runtime_error(image_path + " is stale: it was packed from another version of " + path + fix);
        }
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
        while (pending_public_.take(event)) apply(event);
        while (pending_.take(event)) apply(event);
        backlog_ = false;
    }

    template <class M, class Rng>
    void choose(const M& controllable, const std::vector<M>& allowed, Rng& rng) {
        M enabled = controllable;
        for (std::size_t a = 0; a < state_.size(); ++a) enabled &= allowed[first_state_[a] + state_[a]];
        const unsigned n = enabled.count();
        if (n != 0) apply(enabled.nth(static_cast<unsigned>(rng.next() % n)));
    }

    void apply(unsigned event) {
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

#endif  // SWARMVM_HPP
