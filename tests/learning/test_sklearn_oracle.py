"""The learned check's classifier against scikit-learn, which is the oracle here and only here.

The drone-delivery setting of the OpenSwarm study: features (distance m, mass kg, take-off SoC %),
standardised with the study's mean and deviation, initial fit on its two assumed points, then
one partial_fit per delivery outcome over a long random stream."""

import warnings

import numpy as np
import pytest
from sklearn.exceptions import ConvergenceWarning
from sklearn.linear_model import SGDClassifier

from swarmvm_learn import LinearClassifier

from drone import MEAN, SCALE, SEED_LABELS, SEED_POINTS, delivery_stream


def oracle(**options):
    return SGDClassifier(loss="modified_huber", penalty="l2", alpha=0.01, learning_rate="optimal",
                         shuffle=False, **options)


def standardised(rows):
    return (np.asarray(rows, dtype=float) - np.asarray(MEAN)) / np.asarray(SCALE)


def assert_close(ours, theirs):
    weights = np.asarray(theirs.coef_[0])
    assert np.allclose(ours.weights, weights, rtol=1e-6, atol=1e-12), (ours.weights, weights)
    assert ours.intercept == pytest.approx(theirs.intercept_[0], rel=1e-6, abs=1e-12)
    assert ours.t == theirs.t_


def test_step_size_offset_is_bottous_heuristic():
    model = LinearClassifier(MEAN, SCALE, alpha=0.01)
    assert model.t0 == pytest.approx(31.6227766, rel=1e-9)   # alpha^(-3/4)


def test_initial_fit_matches_sklearn_fit():
    model = LinearClassifier(MEAN, SCALE, alpha=0.01)
    epochs = model.fit(SEED_POINTS, SEED_LABELS)
    reference = oracle().fit(standardised(SEED_POINTS), SEED_LABELS)
    assert epochs == reference.n_iter_ == 87
    assert_close(model, reference)
    assert model.intercept == pytest.approx(6.3246, abs=1e-4)


def test_seven_epochs_give_the_published_weights():
    """STUDIES.md's w = (-7.7631, -7.7631, 7.7631) is the fit after 7 epochs without tol."""
    model = LinearClassifier(MEAN, SCALE, alpha=0.01)
    model.fit(SEED_POINTS, SEED_LABELS, max_iter=7, tol=None)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        reference = oracle(max_iter=7, tol=None).fit(standardised(SEED_POINTS), SEED_LABELS)
    assert_close(model, reference)
    assert model.weights == pytest.approx([-7.7631, -7.7633, 7.7624], abs=1e-4)


@pytest.mark.slow
def test_online_stream_of_10000_matches_sklearn_partial_fit():
    model = LinearClassifier(MEAN, SCALE, alpha=0.01)
    model.fit(SEED_POINTS, SEED_LABELS)
    reference = oracle().fit(standardised(SEED_POINTS), SEED_LABELS)
    disagreements = 0
    decisions = [0, 0]
    for number, (features, label) in enumerate(delivery_stream(10_000, seed=7)):
        row = standardised([features])
        ours = model.decide(features)
        theirs = reference.decision_function(row)[0] >= 0.0
        disagreements += ours != theirs
        decisions[ours] += 1
        model.partial_fit(features, label)
        reference.partial_fit(row, [label])
        if number % 500 == 0:
            assert_close(model, reference)
    assert disagreements == 0
    assert min(decisions) > 1000          # both decisions occur: the test exercises both sides
    assert_close(model, reference)
    bid = model.bid_value(SEED_POINTS[0])
    assert bid == pytest.approx(reference.decision_function(standardised(SEED_POINTS[:1]))[0]
                                / np.linalg.norm(reference.coef_[0]), rel=1e-6)


def test_learning_improves_accuracy_on_the_stream():
    model = LinearClassifier(MEAN, SCALE, alpha=0.01)
    model.fit(SEED_POINTS, SEED_LABELS)
    test = list(delivery_stream(2000, seed=99))
    before = sum(model.decide(x) == bool(y) for x, y in test)
    for features, label in delivery_stream(3000, seed=3):
        model.partial_fit(features, label)
    after = sum(model.decide(x) == bool(y) for x, y in test)
    assert after > before + 100


def test_saved_classifier_round_trips():
    model = LinearClassifier(MEAN, SCALE, alpha=0.01)
    model.fit(SEED_POINTS, SEED_LABELS)
    model.partial_fit((2000, 1, 80), 1)
    copy = LinearClassifier.from_dict(model.to_dict())
    assert copy.to_dict() == model.to_dict()
    assert copy.decision_function((3000, 2, 60)) == model.decision_function((3000, 2, 60))
