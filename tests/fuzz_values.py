"""Random TOML values for the fuzz tests of case files and bearing description files."""

from __future__ import annotations

import random


def random_value(rng: random.Random, numbers, words, keys, max_depth: int, max_items: int, exponent: int,
                 depth: int = 0):
    """A random TOML value: one of ``numbers`` or a random magnitude up to 10^±``exponent``, one of
    ``words``, a boolean, a list, or a table with keys from ``keys`` (nested to ``max_depth``)."""
    def inner():
        return random_value(rng, numbers, words, keys, max_depth, max_items, exponent, depth + 1)

    kind = rng.random()
    if kind < 0.45:
        return rng.choice(numbers) if rng.random() < 0.7 else rng.uniform(-1e3, 1e3) * 10.0 ** rng.randint(-exponent,
                                                                                                          exponent)
    if kind < 0.6:
        return rng.choice(words)
    if kind < 0.68:
        return rng.random() < 0.5
    if kind < 0.88 and depth < max_depth:
        return [inner() for _ in range(rng.randint(0, max_items))]
    if depth < max_depth:
        return {rng.choice(keys): inner() for _ in range(rng.randint(0, max_items))}
    return rng.choice(numbers)
