#!/bin/sh
# Fails when a binary imports a function of CHOLMOD's GPL modules (Supernodal, Modify,
# MatrixOps): the app and CLI must call only the LGPL ones (Core, Cholesky, Check).
# The list is every function declared in /usr/include/suitesparse/cholmod_supernodal.h,
# cholmod_modify.h and cholmod_matrixops.h (SuiteSparse 5.12), int and long ("_l_") versions.
gpl='^cholmod_(l_)?(super_lsolve|super_ltsolve|super_numeric|super_symbolic|super_symbolic2|rowadd|rowadd_mark|rowadd_solve|rowdel|rowdel_mark|rowdel_solve|updown|updown_mark|updown_mask|updown_mask2|updown_solve|drop|horzcat|norm_dense|norm_sparse|scale|sdmult|ssmult|submatrix|symmetry|vertcat)$'
status=0
for binary in "$@"; do
    imports=$(nm -D --undefined-only "$binary" | awk '{print $NF}' | sed 's/@.*//')
    if ! echo "$imports" | grep -q '^cholmod_'; then
        echo "$binary imports no CHOLMOD function: is the check still looking at the solver?"
        status=1
    fi
    found=$(echo "$imports" | grep -E "$gpl")
    if [ -n "$found" ]; then
        echo "$binary calls GPL CHOLMOD functions:" $found
        status=1
    else
        echo "$binary: CHOLMOD functions used:" $(echo "$imports" | grep '^cholmod_' | sort -u)
    fi
done
exit $status
