;;; eglot_client.el --- Emacs + Eglot as the client of `urdflint lsp' -*- lexical-binding: t -*-

;; A real editor as the client of `urdflint lsp' (tests/test_editors.py): Emacs 28+ with Eglot
;; (built into Emacs 29+; on Emacs 28 the GNU ELPA package, Debian's elpa-eglot), in batch:
;;   emacs --batch -Q -l tests/editors/eglot_client.el
;; Opens T_FILE (nxml-mode), connects Eglot to `T_PYTHON -m urdflint lsp --no-cache' with T_ROOT
;; as the project, waits for Flymake's diagnostics, asks the code actions of the first T_CODE
;; diagnostic, applies the "Fix ..." one through `eglot-code-actions' (as M-x would, the
;; completion answered), saves, and waits until that diagnostic is gone. Writes a JSON report
;; to T_OUT. With T_PROBE set it only loads Eglot: exit 0 and its version on stdout, or exit 3.

(require 'cl-lib)
(require 'json)
(require 'package)

(defun urdflint-test--load-eglot ()
  "Load Eglot: built in (Emacs 29+), else a package from the system's ELPA directories
\(Debian's elpa-eglot in /usr/share/emacs/site-lisp/elpa) or ~/.emacs.d/elpa (M-x
package-install from GNU ELPA). Nil when there is none."
  (or (require 'eglot nil t)
      (progn
        (setq package-directory-list
              (cl-remove-if-not
               #'file-directory-p
               (list "/usr/local/share/emacs/site-lisp/elpa"
                     (format "/usr/share/emacs/%s/site-lisp/elpa" emacs-version)
                     "/usr/share/emacs/site-lisp/elpa")))
        (package-initialize)
        (require 'eglot nil t))))

(defun urdflint-test--eglot-version ()
  (let ((desc (cadr (assq 'eglot package-alist))))
    (cond (desc (package-version-join (package-desc-version desc)))
          ((locate-library "eglot") (format "built in (Emacs %s)" emacs-version))
          (t "unknown"))))

(when (getenv "T_PROBE")
  (if (urdflint-test--load-eglot)
      (progn (princ (urdflint-test--eglot-version)) (terpri) (kill-emacs 0))
    (kill-emacs 3)))

(defvar urdflint-test--steps nil)
(defun urdflint-test--step (name value)
  (push `((name . ,name) (value . ,value)) urdflint-test--steps))

(defun urdflint-test--wait (seconds predicate)
  "Let Emacs read the server until PREDICATE is true or SECONDS pass; PREDICATE's value."
  (let ((deadline (+ (float-time) seconds)) (got nil))
    (while (and (not (setq got (funcall predicate))) (< (float-time) deadline))
      (accept-process-output nil 0.02))
    got))

(defun urdflint-test--lsp-diag (diagnostic)
  "The LSP Diagnostic (a plist) Eglot keeps with a Flymake DIAGNOSTIC."
  (cdr (assq 'eglot-lsp-diag (flymake-diagnostic-data diagnostic))))

(defun urdflint-test--with-code (code)
  "Flymake's diagnostics in this buffer whose LSP code is CODE, in buffer order."
  (sort (cl-remove-if-not
         (lambda (d) (equal (plist-get (urdflint-test--lsp-diag d) :code) code))
         (flymake-diagnostics))
        (lambda (a b) (< (flymake-diagnostic-beg a) (flymake-diagnostic-beg b)))))

(defun urdflint-test--run ()
  (let ((file (getenv "T_FILE"))
        (root (file-name-as-directory (getenv "T_ROOT")))
        (code (getenv "T_CODE"))
        (python (getenv "T_PYTHON")))
    (unless (urdflint-test--load-eglot)
      (error "No Eglot: Emacs 29+ has it built in; on Emacs 28 install elpa-eglot (Debian) or M-x package-install RET eglot"))
    (urdflint-test--step "eglot" (urdflint-test--eglot-version))
    ;; README's setup (the server command aside).
    (add-to-list 'auto-mode-alist '("\\.\\(?:urdf\\|xacro\\)\\'" . nxml-mode))
    (add-to-list 'eglot-server-programs
                 `((nxml-mode :language-id "xml") . (,python "-m" "urdflint" "lsp" "--no-cache")))
    (add-hook 'nxml-mode-hook
              (lambda ()
                (when (and buffer-file-name
                           (string-match-p "\\.\\(?:urdf\\|xacro\\)\\'" buffer-file-name))
                  (eglot-ensure))))
    ;; The test's directory is no VCS repository: make it the project (the LSP root).
    (add-hook 'project-find-functions (lambda (_dir) (cons 'transient root)))
    (find-file file)
    (unless (eq major-mode 'nxml-mode) (error "%s opened in %s, not nxml-mode" file major-mode))
    ;; `eglot-ensure' connects when the command that opened the file ends: no command loop
    ;; here, so run what ends one.
    (run-hooks 'post-command-hook)
    (unless (urdflint-test--wait 60 #'eglot-managed-p) (error "Eglot never managed %s" file))
    (flymake-start)
    (urdflint-test--wait 60 (lambda () (urdflint-test--with-code code)))
    (let ((before (urdflint-test--with-code code)))
      (urdflint-test--step "diagnostics" (length (flymake-diagnostics)))
      (urdflint-test--step "with code" (length before))
      (when before
        (let* ((d (car before))
               (actions (eglot-code-actions (flymake-diagnostic-beg d) (flymake-diagnostic-end d)))
               (titles (mapcar (lambda (a) (plist-get a :title)) actions))
               (fix (cl-find-if (lambda (title) (string-prefix-p "Fix " title)) titles)))
          (urdflint-test--step "actions" (vconcat titles))
          (when fix
            ;; M-x eglot-code-actions at the diagnostic, answering its completion with the fix
            ;; (a non-list `last-nonmenu-event': a keyboard command, no popup menu).
            (let ((last-nonmenu-event ?\r))
              (cl-letf (((symbol-function 'completing-read) (lambda (&rest _) fix)))
                (eglot-code-actions (flymake-diagnostic-beg d) (flymake-diagnostic-end d) nil t)))
            (save-buffer)
            (let ((gone (urdflint-test--wait
                         60 (lambda () (< (length (urdflint-test--with-code code))
                                          (length before))))))
              (urdflint-test--step "fixed" (if gone t :json-false))
              (urdflint-test--step "with code after" (length (urdflint-test--with-code code))))))))
    (ignore-errors (eglot-shutdown (eglot-current-server)))))

(let ((report nil))
  (condition-case err
      (progn (urdflint-test--run)
             (setq report `((ok . t))))
    (error (setq report `((ok . :json-false) (error . ,(error-message-string err))))))
  (setq report (append report `((steps . ,(vconcat (reverse urdflint-test--steps))))))
  (with-temp-file (getenv "T_OUT") (insert (json-encode report)))
  (kill-emacs 0))

;;; eglot_client.el ends here
