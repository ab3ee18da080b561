# Compositions in the add-on: its three properties (at%, wt% and karat of the first
# element) and the atomic fraction x they set, by the library's rules (core/src/
# composition.cc: ParseComposition's 75at%, 75wt% and 18k, with their ranges). Plain
# Python without bpy, so that tests/composition_parsers_test.cc checks it against the
# library on the list the explorer page is checked on (tests/reference/
# composition_inputs.json).

# The range of each property, as the library's: at% and wt% 0-100, karat 0-24.
PERCENT_RANGE = (0.0, 100.0)
KARAT_RANGE = (0.0, 24.0)


def weight_fraction(x, masses):
    """Weight fraction of the first element at atomic fraction x."""
    a, b = x * masses[0], (1.0 - x) * masses[1]
    return a / (a + b) if a + b > 0 else 0.0


def atomic_fraction(w, masses):
    """Atomic fraction of the first element at weight fraction w."""
    a, b = w / masses[0], (1.0 - w) / masses[1]
    return a / (a + b) if a + b > 0 else 0.0


def karat_from_x(x, masses, gold_element):
    """Karat at atomic fraction x; gold_element 0: the first element is gold, 1: the second."""
    w = weight_fraction(x, masses)
    return 24.0 * (w if gold_element == 0 else 1.0 - w)


def x_from_karat(k, masses, gold_element):
    w = k / 24.0
    return atomic_fraction(w if gold_element == 0 else 1.0 - w, masses)


def x_from_property(unit, value, masses, gold_element=-1):
    """The atomic fraction a property's value sets: unit "AT", "WT" or "KARAT"; None where
    the library refuses the value (outside the property's range, or a karat without
    gold)."""
    lo, hi = KARAT_RANGE if unit == "KARAT" else PERCENT_RANGE
    if not lo <= value <= hi:
        return None
    if unit == "AT":
        return value / 100.0
    if unit == "WT":
        return atomic_fraction(value / 100.0, masses)
    if unit == "KARAT" and gold_element in (0, 1):
        return x_from_karat(value, masses, gold_element)
    return None
