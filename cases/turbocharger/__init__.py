"""The turbocharger rotor on two angular-contact ball bearings in squeeze-film dampers (:mod:`.case`)."""
