"""Centreline drag of a sphere in a cylindrical pore (spec 70 §7.4; external literature, "verify against
the originals before use"): the enhanced axial drag K(lambda) of a sphere of radius R on the axis of a
pore of radius R_pore, lambda = R/R_pore, which the pore-frame S_z(beta -> 0) of spec 40 §9 should
approach."""


def haberman_sayre(lam):
    """K = (1 - 0.75857 l^5) / (1 - 2.1050 l + 2.0865 l^3 - 1.7068 l^5 + 0.72603 l^6)."""
    return (1 - 0.75857 * lam ** 5) / (1 - 2.1050 * lam + 2.0865 * lam ** 3 - 1.7068 * lam ** 5 + 0.72603 * lam ** 6)


def bohlin(lam):
    """1/K = 1 - 2.10444 l + 2.08877 l^3 - 0.94813 l^5 - 1.372 l^6 + 3.87 l^8 - 4.19 l^10."""
    return 1.0 / (1 - 2.10444 * lam + 2.08877 * lam ** 3 - 0.94813 * lam ** 5 - 1.372 * lam ** 6 + 3.87 * lam ** 8 - 4.19 * lam ** 10)


FORMULAS = {"haberman_sayre": haberman_sayre, "bohlin": bohlin}
LABELS = {"haberman_sayre": "Haberman-Sayre", "bohlin": "Bohlin"}
