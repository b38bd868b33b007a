"""The Mohr-Coulomb envelope from confined compression tests.

A straight envelope tau = c + sigma tan(phi) in principal stresses is the line
    sigma_1 = sigma_c + k sigma_3,  k = (1 + sin phi) / (1 - sin phi),  sigma_c = 2 c sqrt(k),
so sigma_c = 2 c cos(phi) / (1 - sin(phi)) is the uniaxial strength the envelope predicts (Jaeger,
Cook and Zimmerman, Fundamentals of Rock Mechanics, 4th ed., eq. 4.4.3-4.4.5). The fit is the
least-squares line through (sigma_3, sigma_1); compression positive.
"""
import math


def line_fit(xs, ys):
    """Least-squares y = a + b x: (a, b, standard error of a, standard error of b). The standard
    errors need three points or more (NaN otherwise)."""
    n = len(xs)
    if n < 2 or len(ys) != n:
        raise ValueError("a line needs two points or more")
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    if sxx <= 0:
        raise ValueError("the confining stresses must differ")
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    a = my - b * mx
    if n < 3:
        return a, b, math.nan, math.nan
    s2 = sum((y - a - b * x) ** 2 for x, y in zip(xs, ys)) / (n - 2)
    return a, b, math.sqrt(s2 * (1.0 / n + mx * mx / sxx)), math.sqrt(s2 / sxx)


def from_line(sigma_c, k):
    """(cohesion c, friction angle phi [deg]) of sigma_1 = sigma_c + k sigma_3. k < 1 (the
    strength falls with confinement) gives a negative angle: no Mohr-Coulomb material, reported
    as measured."""
    if k <= 0:
        return math.nan, math.nan
    sin_phi = (k - 1.0) / (k + 1.0)
    return sigma_c / (2.0 * math.sqrt(k)), math.degrees(math.asin(sin_phi))


def uniaxial_strength(c, phi_deg):
    """sigma_c = 2 c cos(phi) / (1 - sin(phi))."""
    phi = math.radians(phi_deg)
    return 2.0 * c * math.cos(phi) / (1.0 - math.sin(phi))
