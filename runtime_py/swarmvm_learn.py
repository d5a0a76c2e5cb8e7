"""swarmvm learning: an online linear classifier for learned checks and a learned selection policy.

Standard library only, like swarmvm_vm.py, so both files can be copied onto a robot together;
the parameters' checksum is the image format's own (swarmvm_format.crc16, the file beside it).
The C twin is runtime_c/swarmvm_learn.{h,c}; docs/learning.md specifies both.

- :class:`LinearClassifier` is the drone-delivery bidding policy of the OpenSwarm study: features
  standardised with a known mean and deviation, decision ``f(x) = w.x + b``, bid iff ``f >= 0``,
  bid value ``f / ||w||``, trained by SGD on the modified Huber loss with an L2 penalty and the
  "optimal" step size ``1 / (alpha (t0 + t - 1))``. It reproduces scikit-learn's
  ``SGDClassifier(loss="modified_huber", penalty="l2", learning_rate="optimal")`` numerically
  (``fit`` with ``shuffle=False`` and ``partial_fit``), including its scaled-weight-vector
  arithmetic, so that a robot needs no scikit-learn.
- :class:`LearnedPolicy` is the VM's ``learned`` selection policy: a softmax over integer
  preferences indexed by (supervisor state, controllable event), trained by REINFORCE with a
  baseline from an operator's reward. It is integer fixed point throughout so the C runtime
  makes bit-identical choices for the same seed and rewards.
"""

import json
import math
import os
from typing import TYPE_CHECKING, Iterable, List, Mapping, Optional, Protocol, Sequence, Set, Tuple, TypedDict, Union

if TYPE_CHECKING:   # mypy reads the format as the package's module; a robot imports the copy beside it
    from runtime_py.swarmvm_format import MAX_SOURCE_FILE_SIZE, Image, crc16, read_file, write_file
else:
    from swarmvm_format import MAX_SOURCE_FILE_SIZE, crc16, read_file, write_file

__all__ = ["LinearClassifier", "LearnedPolicy", "PolicyError", "q16"]


# ---------------------------------------------------------------------------------------------
# Online linear classifier (floating point; matches scikit-learn's plain SGD)
# ---------------------------------------------------------------------------------------------

WSCALE_RESET = 1e-9      # scikit-learn rescales its weight vector when the scale drops below this
MAX_DLOSS = 1e12         # and clips the loss gradient to +-this

Features = Sequence[float]      # one sample, in the classifier's raw (unstandardised) units
StrPath = Union[str, "os.PathLike[str]"]


class ClassifierState(TypedDict):
    """:meth:`LinearClassifier.to_dict`: everything a classifier needs to go on learning."""
    mean: List[float]
    scale: List[float]
    alpha: float
    weights: List[float]
    intercept: float
    t: float


def _huber_loss(y: float, p: float) -> float:
    """Modified Huber loss for a label y in {-1, +1} and a decision value p."""
    z = p * y
    if z >= 1.0:
        return 0.0
    if z >= -1.0:
        return (1.0 - z) * (1.0 - z)
    return -4.0 * z


def _huber_gradient(y: float, p: float) -> float:
    """d loss / d p of :func:`_huber_loss`."""
    z = p * y
    if z >= 1.0:
        return 0.0
    if z >= -1.0:
        return 2.0 * (1.0 - z) * -y
    return -4.0 * y


class LinearClassifier:
    """Binary linear classifier ``f(x) = w . ((x - mean) / scale) + b`` learned online.

    Labels are 1 (positive: capable, delivered) and 0 (negative). ``alpha`` is the L2 strength;
    the step at update t (counted from 1 over the classifier's whole life) is
    ``1 / (alpha (t0 + t - 1))`` with ``t0 = 1 / (alpha * typw)``, ``typw = sqrt(1 / sqrt(alpha))``
    (Bottou's heuristic as scikit-learn applies it)."""

    def __init__(self, mean: Features, scale: Features, alpha: float = 0.01) -> None:
        if len(mean) != len(scale) or not mean:
            raise ValueError("mean and scale must be non-empty and of equal length")
        if alpha <= 0:
            raise ValueError("alpha must be positive")
        self.mean = [float(m) for m in mean]
        self.scale = [float(s) for s in scale]
        self.alpha = float(alpha)
        self.weights = [0.0] * len(mean)
        self.intercept = 0.0
        self.t = 1.0                          # scikit-learn's t_: the next update's count
        typw = math.sqrt(1.0 / math.sqrt(self.alpha))
        # scikit-learn: eta0 = typw / max(1, dloss(y=1, p=-typw)); the gradient is <= 0 for y = 1
        self.t0 = 1.0 / (typw / max(1.0, _huber_gradient(1.0, -typw)) * self.alpha)

    @property
    def n_features(self) -> int:
        return len(self.mean)

    def standardise(self, features: Features) -> List[float]:
        if len(features) != self.n_features:
            raise ValueError("expected %d features, got %d" % (self.n_features, len(features)))
        return [(float(x) - m) / s for x, m, s in zip(features, self.mean, self.scale)]

    # -- decisions ------------------------------------------------------------------------------
    def decision_function(self, features: Features) -> float:
        """f(x) on raw (unstandardised) features."""
        return self._dot(self.standardise(features), self.weights, 1.0) + self.intercept

    def decide(self, features: Features) -> bool:
        """The bidding decision: True iff f(x) >= 0."""
        return self.decision_function(features) >= 0.0

    def norm(self) -> float:
        """||w||, the intercept excluded."""
        return math.sqrt(sum(w * w for w in self.weights))

    def bid_value(self, features: Features) -> float:
        """f(x) / ||w||: the signed distance of x from the decision hyperplane (0 if w = 0)."""
        norm = self.norm()
        return self.decision_function(features) / norm if norm > 0.0 else 0.0

    # -- learning -------------------------------------------------------------------------------
    def fit(self, samples: Iterable[Features], labels: Iterable[int], max_iter: int = 1000, tol: Optional[float] = 1e-3,
            n_iter_no_change: int = 5) -> int:
        """Train from scratch as ``SGDClassifier.fit`` with ``shuffle=False`` does: epochs over the
        samples in order until the mean objective fails to improve by ``tol`` for
        ``n_iter_no_change`` epochs in a row (``tol=None`` runs all ``max_iter``). Returns the
        number of epochs run."""
        xs = [self.standardise(x) for x in samples]
        ys = [self._sign(label) for label in labels]
        self.weights = [0.0] * self.n_features
        self.intercept = 0.0
        self.t = 1.0
        epochs = self._sgd(xs, ys, max_iter, tol, n_iter_no_change)
        self.t += epochs * len(xs)
        return epochs

    def partial_fit(self, features: Features, label: int) -> None:
        """One SGD update on one labelled sample (``SGDClassifier.partial_fit`` on one row)."""
        self._sgd([self.standardise(features)], [self._sign(label)], 1, None, 1)
        self.t += 1.0

    @staticmethod
    def _sign(label: int) -> float:
        if label not in (0, 1, True, False):
            raise ValueError("labels are 1 (positive) or 0 (negative), got %r" % (label,))
        return 1.0 if label else -1.0

    @staticmethod
    def _dot(x: Sequence[float], v: Sequence[float], wscale: float) -> float:
        total = 0.0
        for a, b in zip(v, x):
            total += a * b
        return total * wscale

    def _sgd(self, xs: Sequence[Sequence[float]], ys: Sequence[float], max_iter: int, tol: Optional[float],
             n_iter_no_change: int) -> int:
        """scikit-learn's plain SGD loop for this loss and penalty, dense data, no averaging.

        The weights are kept as ``wscale * v`` during the call (the L2 shrink only touches the
        scalar) and folded back at the end, exactly as scikit-learn's WeightVector does, so the
        rounding matches too."""
        v = list(self.weights)
        wscale = 1.0
        sq_norm = sum(a * a for a in v)
        t = self.t
        best = math.inf
        no_improvement = 0
        epoch = 0
        for epoch in range(1, max_iter + 1):
            objective = 0.0
            for x, y in zip(xs, ys):
                p = self._dot(x, v, wscale) + self.intercept
                eta = 1.0 / (self.alpha * (self.t0 + t - 1.0))
                objective += _huber_loss(y, p)
                objective += self.alpha * (0.5 * math.sqrt(sq_norm) ** 2)
                dloss = min(max(_huber_gradient(y, p), -MAX_DLOSS), MAX_DLOSS)
                update = -eta * dloss
                shrink = max(0.0, 1.0 - eta * self.alpha)
                wscale *= shrink
                sq_norm *= shrink * shrink
                if wscale < WSCALE_RESET:
                    v = [a * wscale for a in v]
                    wscale = 1.0
                if update != 0.0:
                    step = update / wscale
                    v = [a + b * step for a, b in zip(v, x)]
                    sq_norm = sum(a * a for a in v) * (wscale * wscale)
                    self.intercept += update
                t += 1.0
            if tol is not None and objective / len(xs) > best - tol:
                no_improvement += 1
            else:
                no_improvement = 0
            best = min(best, objective / len(xs))
            if no_improvement >= n_iter_no_change:
                break
        self.weights = [a * wscale for a in v]
        return epoch

    # -- persistence ----------------------------------------------------------------------------
    def to_dict(self) -> ClassifierState:
        return ClassifierState(mean=self.mean, scale=self.scale, alpha=self.alpha, weights=self.weights,
                               intercept=self.intercept, t=self.t)

    @classmethod
    def from_dict(cls, data: ClassifierState) -> "LinearClassifier":
        model = cls(data["mean"], data["scale"], data["alpha"])
        model.weights = [float(w) for w in data["weights"]]
        model.intercept = float(data["intercept"])
        model.t = float(data["t"])
        return model


# ---------------------------------------------------------------------------------------------
# Learned selection policy (integer fixed point; bit-identical with the C runtime)
# ---------------------------------------------------------------------------------------------

Q16_ONE = 1 << 16
Q15_ONE = 1 << 15
THETA_LIMIT = 32 << 16           # preferences are clamped to +-32.0
REWARD_LIMIT = 1 << 24           # rewards are clamped to +-256.0
ADVANTAGE_LIMIT = (1 << 22) - 1  # and advantages to about +-64.0
DIFF_LIMIT = 0x7FFF              # preference gaps beyond 127.99 count as 127.99
EXP_CUTOFF = 16 << 16            # exp(-x) for x >= 16 is below one Q15 unit: weight 0
LOG2E_Q14 = 23637                # log2(e) in Q14
# 2^(-j/16) in Q15 for j = 0..16: the table of the fixed-point exponential.
EXP2_TABLE = tuple(int(math.floor(32768 * 2.0 ** (-j / 16.0) + 0.5)) for j in range(17))
POLICY_MAGIC = 0x53564C50        # "SVLP": first word of a saved parameter array
POLICY_VERSION = 1


class PolicyError(ValueError):
    """Parameters that do not fit this supervisor or fail their checksum."""


def q16(value: float) -> int:
    """A real number as the Q16.16 integer the policy uses (round half away from zero)."""
    scaled = value * Q16_ONE
    return int(math.floor(scaled + 0.5)) if scaled >= 0 else -int(math.floor(-scaled + 0.5))


def _floor_shift(value: int, bits: int) -> int:
    """Arithmetic right shift (floor division by 2^bits); the C code spells it out portably."""
    return value >> bits


def _clamp(value: int, limit: int) -> int:
    return -limit if value < -limit else limit if value > limit else value


def exp_neg_q15(x: int) -> int:
    """exp(-x) in Q15 for x >= 0 in Q16: 2^-(x log2 e) by table and linear interpolation."""
    if x >= EXP_CUTOFF:
        return 0
    y = ((x >> 4) * LOG2E_Q14) >> 10        # x log2(e) in Q16
    whole, frac = y >> 16, y & 0xFFFF
    j, r = frac >> 12, frac & 0xFFF
    value = EXP2_TABLE[j] - (((EXP2_TABLE[j] - EXP2_TABLE[j + 1]) * r) >> 12)
    return value >> whole


# A choice waiting for its reward: the theta rows of the states it was made in, the ranks of the
# enabled events, their probabilities in Q15, and the position of the one chosen.
Choice = Tuple[List[int], List[int], List[int], int]


class Generator(Protocol):
    def next(self) -> int: ...


class ChoosingVM(Protocol):
    """What the policy reads of the VM that asks it to choose (swarmvm_vm.VM, the reference VM)."""

    @property
    def states(self) -> Sequence[int]: ...

    @property
    def rng(self) -> Generator: ...


class LearnedPolicy:
    """Softmax selection over preferences ``theta[global state][controllable event]``.

    The preference of enabled event e is ``h(e) = sum over supervisors s of
    theta[first_state(s) + cur(s)][rank(e)]`` (one-hot features of each supervisor's state).
    Probabilities follow ``exp(beta (h(e) - max h))`` in Q15 and the draw is the VM's own
    xorshift32, as the ``weighted`` policy draws. :meth:`reward` applies REINFORCE with a
    running-average baseline to the last choice. All numbers are integers: see docs/learning.md.

    ``inv_temp_q8`` is 1/temperature in Q8.8 (256 = temperature 1), ``rate_q16`` the learning
    rate in Q16 (below 1.0), ``baseline_shift`` the baseline's averaging rate 2^-shift."""

    def __init__(self, image: "Image", inv_temp_q8: int = 256, rate_q16: int = q16(0.1), baseline_shift: int = 4) -> None:
        if not 1 <= inv_temp_q8 <= 0xFFFF:
            raise ValueError("inv_temp_q8 must be in 1..65535")
        if not 0 <= rate_q16 <= 0xFFFF:
            raise ValueError("rate_q16 must be in 0..65535 (below 1.0)")
        if not 0 <= baseline_shift <= 15:
            raise ValueError("baseline_shift must be in 0..15")
        self.inv_temp_q8, self.rate_q16, self.baseline_shift = inv_temp_q8, rate_q16, baseline_shift
        self.sup_first = list(image.sup_first_state)
        self.num_states = len(image.state_defined)
        self.controllable = [e for e in range(image.num_events) if image.controllable >> e & 1]
        self.rank = {e: r for r, e in enumerate(self.controllable)}
        self.theta = [0] * (self.num_states * len(self.controllable))
        self.baseline = 0
        self.updates = 0
        self.pending: Optional[Choice] = None

    @classmethod
    def with_temperature(cls, image: "Image", temperature: float = 1.0, rate: float = 0.1,
                         baseline_shift: int = 4) -> "LearnedPolicy":
        """Convenience: real temperature and rate, converted once to the integer options."""
        beta = max(1, min(0xFFFF, int(math.floor(256.0 / temperature + 0.5))))
        return cls(image, beta, max(0, min(0xFFFF, q16(rate))), baseline_shift)

    # -- choosing -------------------------------------------------------------------------------
    def _rows(self, states: Sequence[int]) -> List[int]:
        width = len(self.controllable)
        return [(self.sup_first[s] + state) * width for s, state in enumerate(states)]

    def preferences(self, states: Sequence[int], enabled: Sequence[int]) -> List[int]:
        rows = self._rows(states)
        return [sum(self.theta[row + self.rank[e]] for row in rows) for e in enabled]

    def weights(self, states: Sequence[int], enabled: Sequence[int]) -> List[int]:
        """Unnormalised Q15 weights of the enabled events (the best one weighs 32768)."""
        prefs = self.preferences(states, enabled)
        top = max(prefs)
        return [exp_neg_q15(min((top - h) >> 8, DIFF_LIMIT) * self.inv_temp_q8) for h in prefs]

    def choose(self, vm: ChoosingVM, enabled: Sequence[int]) -> int:
        """The VM's hook for policy ``learned``: draw an enabled event, remember the choice."""
        if len(enabled) == 1:
            self.pending = None
            return enabled[0]
        weights = self.weights(vm.states, enabled)
        total = sum(weights)
        pick = vm.rng.next() % total
        position = 0
        while pick >= weights[position]:
            pick -= weights[position]
            position += 1
        probs = [(w * Q15_ONE) // total for w in weights]
        self.pending = (self._rows(vm.states), [self.rank[e] for e in enabled], probs, position)
        return enabled[position]

    # -- learning -------------------------------------------------------------------------------
    def reward(self, value: int) -> bool:
        """Credit the last choice with an integer reward in Q16 (use :func:`q16` for reals).

        Without a pending choice (none made since the last reward, or it had no alternative)
        the reward is ignored and False returned."""
        if not isinstance(value, int):
            raise TypeError("the reward is a Q16 integer: pass q16(%r)" % (value,))
        if self.pending is None:
            return False
        rows, ranks, probs, chosen = self.pending
        self.pending = None
        value = _clamp(value, REWARD_LIMIT)
        advantage = _clamp(value - self.baseline, ADVANTAGE_LIMIT)
        self.baseline += _floor_shift(value - self.baseline, self.baseline_shift)
        step = _floor_shift(advantage, 8) * self.rate_q16       # Q8 x Q16
        step9 = _floor_shift(step, 15)                           # Q24 -> Q9
        for position, (rank, prob) in enumerate(zip(ranks, probs)):
            delta = _floor_shift(step9 * ((Q15_ONE if position == chosen else 0) - prob), 8)
            for row in rows:
                index = row + rank
                self.theta[index] = _clamp(self.theta[index] + delta, THETA_LIMIT)
        self.updates += 1
        return True

    # -- persistence ----------------------------------------------------------------------------
    def to_words(self) -> List[int]:
        """The flat array the C runtime loads: header, baseline, theta, then a CRC word."""
        words = [POLICY_MAGIC, POLICY_VERSION, len(self.theta), self.inv_temp_q8, self.rate_q16,
                 self.baseline_shift, self.baseline & 0xFFFFFFFF, self.updates]
        words += [value & 0xFFFFFFFF for value in self.theta]
        words.append(crc16(b"".join(w.to_bytes(4, "little") for w in words)))
        return words

    def from_words(self, saved: Iterable[int]) -> None:
        """Load :meth:`to_words` output (from Python or C); PolicyError if it does not fit."""
        words = [int(w) & 0xFFFFFFFF for w in saved]
        if len(words) < 9 or words[0] != POLICY_MAGIC or words[1] != POLICY_VERSION:
            raise PolicyError("not a swarmvm learned-policy parameter array")
        if words[2] != len(self.theta) or len(words) != 9 + words[2]:
            raise PolicyError("parameters for %d preferences, this supervisor has %d" % (words[2], len(self.theta)))
        if crc16(b"".join(w.to_bytes(4, "little") for w in words[:-1])) != words[-1]:
            raise PolicyError("parameter checksum mismatch")
        signed = [w - (1 << 32) if w >> 31 else w for w in words]
        # Values the policy never holds, refused as the C loader refuses them (svl_policy_load's
        # plausible()): a matching checksum does not make an array this policy's.
        if words[3] > 0xFFFF or words[4] > 0xFFFF or words[5] >= 32 or abs(signed[6]) > REWARD_LIMIT \
                or any(abs(value) > THETA_LIMIT for value in signed[8:-1]):
            raise PolicyError("parameter values out of the policy's range")
        self.inv_temp_q8, self.rate_q16, self.baseline_shift = words[3], words[4], words[5]
        self.baseline, self.updates = signed[6], words[7]
        self.theta = signed[8:-1]
        self.pending = None

    def save(self, path: StrPath) -> None:
        # the runtime's writer: the whole file or the old one, never half a policy
        write_file(path, json.dumps(dict(format="swarmvm-learned-policy", words=self.to_words())).encode("ascii"))

    def load(self, path: StrPath) -> None:
        raw = read_file(path, MAX_SOURCE_FILE_SIZE)     # the runtime's input layer: regular files, bounded
        if len(raw) > MAX_SOURCE_FILE_SIZE:
            raise PolicyError("%s is over %d bytes: not a saved learned policy" % (path, MAX_SOURCE_FILE_SIZE))
        data = json.loads(raw.decode("utf-8"))
        if data.get("format") != "swarmvm-learned-policy":
            raise PolicyError("%s is not a saved learned policy" % path)
        self.from_words(data["words"])


class LearnedCheck:
    """One learned pair of uncontrollable events (docs/learning.md): a pending question, its
    cached answer and the features of the last "yes"."""

    def __init__(self, classifier: LinearClassifier) -> None:
        self.classifier = classifier
        self.pending: Optional[List[float]] = None     # the question's features, until both events polled
        self.answer: Optional[bool] = None
        self.polled: Set[bool] = set()                 # which of yes (True) and no (False) asked it
        self.last_yes: Optional[List[float]] = None
        self.decisions = 0

    def offer(self, features: Features) -> None:
        self.pending, self.answer, self.polled = list(features), None, set()

    def poll(self, yes: bool) -> bool:
        """The check of the yes (``yes=True``) or no event: both are polled in one step, both
        see the same answer, and the question is consumed once both have been asked."""
        if self.pending is None:
            return False
        if self.answer is None:
            self.answer = self.classifier.decide(self.pending)
            self.decisions += 1
        self.polled.add(yes)
        result = self.answer if yes else not self.answer
        if len(self.polled) == 2:
            if self.answer:
                self.last_yes = self.pending
            self.pending = None
        return result

    def report_outcome(self, success: bool, features: Optional[Features] = None) -> None:
        """One online update: label 1 on success, 0 on failure."""
        learned = self.last_yes if features is None else features
        if learned is None:
            raise ValueError("no decided features to learn from: pass features=")
        self.classifier.partial_fit(learned, 1 if success else 0)


class LearnedChecks:
    """Controller mixin for the learned pairs ``pairs`` ((yes event, no event), ...): a generated
    subclass adds one ``check_<event>`` per event, bound to the VM like any other check.
    ``classifiers`` maps each pair's yes event to its classifier."""

    pairs: Tuple[Tuple[str, str], ...] = ()

    def __init__(self, classifiers: Optional[Mapping[str, LinearClassifier]]) -> None:
        given = classifiers or {}
        missing = [yes for yes, _ in self.pairs if yes not in given]
        if missing:
            example = ", ".join("%r: swarmvm_learn.LinearClassifier(mean, scale, alpha)" % yes for yes in missing)
            raise ValueError("learned checks need a classifier each: classifiers={" + example + "}")
        self.learned = {yes: LearnedCheck(given[yes]) for yes, _ in self.pairs}

    def offer(self, yes_event: str, features: Features) -> None:
        """Pose the question of a pair (features in the classifier's raw units)."""
        self.learned[yes_event].offer(features)

    def report_outcome(self, yes_event: str, success: bool, features: Optional[Features] = None) -> None:
        self.learned[yes_event].report_outcome(success, features)
