"""Cases of cylindrical roller bearings (``family = "crb"``): friction torque, contact by contact."""
