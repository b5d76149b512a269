"""The game's two roles, in the order the C++ side numbers its agents (pursuers first)."""

ROLES = ("pursuer", "evader")


def other_role(role):
    """The role that plays against `role` (a ValueError for a name that is not a role)."""
    return ROLES[1 - ROLES.index(role)]
