// swarmvm C++ runtime, the table image (docs/image-format.md): its checksum, the reader's
// refusals (ImageError, with swarmvm_format.hpp's ErrorCode; UnknownEvent for a name it lacks),
// the event set BasicMask, and Image, whose parse() checks an image as every runtime does.
// Header only, C++17, standard library only; swarmvm.hpp includes it with the VM
// (swarmvm_vm.hpp) and the compatibility layer (swarmvm_compat.hpp). The format's numbers are
// swarmvm_format.hpp's, generated from runtime_py/swarmvm_format.py; generated image headers
// refuse to compile against a runtime of another version.
#ifndef SWARMVM_IMAGE_HPP
#define SWARMVM_IMAGE_HPP

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "swarmvm_format.hpp"

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#define SWARMVM_POSIX_FILES 1
#endif

// Keeps a rare path out of a hot loop (GCC and Clang; elsewhere the compiler decides).
#if defined(__GNUC__) || defined(__clang__)
#define SWARMVM_NOINLINE __attribute__((noinline))
#define SWARMVM_INLINE __attribute__((always_inline)) inline
#else
#define SWARMVM_NOINLINE
#define SWARMVM_INLINE inline
#endif

namespace swarmvm {

// CRC-16/MCRF4XX (reflected polynomial 0x8408, initial 0xFFFF, no final xor): what the
// Kilobot's avr-libc computes with _crc_ccitt_update, so every runtime checks the same sum. A
// byte at a time, branch-free (the byte-wise form of the polynomial, as swarmvm.c computes it).
inline std::uint16_t crc16(const std::uint8_t* data, std::size_t size, std::uint16_t crc = kCrc16Init) {
    for (std::size_t i = 0; i < size; ++i) {
        auto d = static_cast<std::uint8_t>(data[i] ^ static_cast<std::uint8_t>(crc));
        d = static_cast<std::uint8_t>(d ^ static_cast<std::uint8_t>(d << 4));
        crc = static_cast<std::uint16_t>(((static_cast<unsigned>(d) << 8) | (crc >> 8)) ^ (d >> 4) ^
                                         (static_cast<unsigned>(d) << 3));
    }
    return crc;
}

// A table image that cannot be run; code() says why, what() says where.
class ImageError : public std::runtime_error {
public:
    ImageError(ErrorCode code, const std::string& what) : std::runtime_error(what), code_(code) {}
    ErrorCode code() const { return code_; }

private:
    ErrorCode code_;
};

// The C++ runtime's input layer (docs/security.md, "The input layer"): every file the runtime
// reads (Image::load, load_beside's image and supervisor.yaml) goes through read_regular_file.
// A path that cannot be opened, or is not a regular file, is a FileError: one line naming it.
class FileError : public std::runtime_error {
public:
    FileError(const std::string& what, bool opened) : std::runtime_error(what), opened_(opened) {}
    // false: the file could not be opened at all (missing, unreadable); true: opened and refused.
    bool opened() const { return opened_; }

private:
    bool opened_;
};

// A supervisor.yaml is read up to the compiler's input limit (swarmvm.boundary.errors.MAX_BYTES):
// one larger cannot be the file an image was packed from.
constexpr std::size_t kMaxSourceFileSize = std::size_t{1} << 20;

namespace detail {

// `text` with each control character as \xHH, so that a message naming a path stays one line.
inline std::string printable(const std::string& text) {
    static const char hex[] = "0123456789abcdef";
    std::string out;
    for (unsigned char c : text) {
        if (c < 0x20 || c == 0x7F) {
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 0xF];
        } else {
            out += static_cast<char>(c);
        }
    }
    return out;
}

}  // namespace detail

// At most `limit` + 1 bytes of the regular file `path` (`what` names it in messages: "table
// image"), so that the caller refuses a longer file in its own words (an image: LENGTH) without
// reading it all. Opened with O_NONBLOCK and checked with fstat before any read: a FIFO with no
// writer (which a plain open waits on for ever), a device (/dev/zero), a folder or a socket is
// refused at once, FileError "what PATH: is a FIFO, not a regular file". Without POSIX (no FIFOs
// or devices by path there), a bounded std::ifstream read.
inline std::string read_regular_file(const std::string& path, std::size_t limit, const std::string& what) {
    const std::string name = what + " " + detail::printable(path);
    std::string bytes(limit + 1, '\0');
    std::size_t got = 0;
#if defined(SWARMVM_POSIX_FILES)
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) throw FileError("cannot read " + name + " (" + std::strerror(errno) + ")", false);
    struct stat info {};
    if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
        const int error = errno;
        const mode_t mode = info.st_mode;
        ::close(fd);
        if (mode == 0) throw FileError("cannot read " + name + " (" + std::strerror(error) + ")", true);
        const char* kind = S_ISDIR(mode) ? "a folder" : S_ISCHR(mode) ? "a character device"
                         : S_ISBLK(mode) ? "a block device" : S_ISFIFO(mode) ? "a FIFO"
                         : S_ISSOCK(mode) ? "a socket" : "an unknown kind of file";
        throw FileError(name + ": is " + kind + ", not a regular file", true);
    }
    while (got < bytes.size()) {
        const ssize_t n = ::read(fd, &bytes[got], bytes.size() - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            const int error = errno;
            ::close(fd);
            throw FileError("cannot read " + name + " (" + std::strerror(error) + ")", true);
        }
        if (n == 0) break;
        got += static_cast<std::size_t>(n);
    }
    ::close(fd);
#else
    std::ifstream in(path, std::ios::binary);
    if (!in) throw FileError("cannot read " + name, false);
    in.read(&bytes[0], static_cast<std::streamsize>(bytes.size()));
    got = static_cast<std::size_t>(in.gcount());
#endif
    bytes.resize(got);
    return bytes;
}

// A callback registered under a name the supervisor does not have (never mapped to event 0).
class UnknownEvent : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
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

    // Reads a .svm file through read_regular_file (a regular file only; at most kMaxImageSize + 1
    // bytes: a huge file is refused, LENGTH, without reading it all) and parses it. FileError (a
    // std::runtime_error) when the file cannot be read or is not a regular file.
    static Image load(const std::string& path) {
        const std::string bytes = read_regular_file(path, kMaxImageSize, "table image");
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

}  // namespace swarmvm

#endif  // SWARMVM_IMAGE_HPP
