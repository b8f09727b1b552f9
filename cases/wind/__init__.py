"""The 12 MW wind main bearing case (three-row cylindrical roller bearing)."""
