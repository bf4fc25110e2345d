;;; editor_latency.el --- urdflint lsp in a real Emacs + Eglot: diagnostics latency -*- lexical-binding: t -*-

;; The Emacs half of bench/editor_latency.py, which runs
;;   emacs -nw -Q -l bench/editor_latency.el
;; in a pseudo-terminal and types its keys: a real interactive Emacs, whose idle timers run as
;; in a session at a keyboard (Eglot sends a change after `eglot-send-changes-idle-time' of
;; idleness, Flymake restarts after `flymake-no-changes-timeout'; both need a command loop
;; with real input, which `emacs --batch' has not). The script writes the key it wants next
;; ("open", "plant N", "revert N", "done") to B_WANT; the harness answers with C-c o, C-c p,
;; C-c r. Each command times from its own start:
;;   open:   find-file B_FILE (Eglot connects when the command ends, `eglot-ensure') -> the
;;           first publishDiagnostics for the file, -> the first Flymake diagnostics shown,
;;           -> the server quiet (no publish for B_QUIET s);
;;   plant:  line B_LINE (0-based) becomes B_PLANTED -> a publish for the file, handled by
;;           Eglot (and handed to Flymake), with more B_CODE diagnostics than as opened;
;;   revert: the line back -> one with as many as then.
;; B_CMD is the server command as a JSON array; B_ROOT the project (workspace folder);
;; B_ROUNDS the plant/revert rounds; B_IDLE, if set, `eglot-send-changes-idle-time'; B_EVAL,
;; if set, a form evaluated after this setup.
;; Writes a JSON report to B_OUT. The file is never saved (no backup, lock or auto-save file).

(require 'cl-lib)
(require 'json)
(require 'package)
(require 'subr-x)
(require 'url-util)

(setq inhibit-startup-screen t
      make-backup-files nil
      create-lockfiles nil
      auto-save-default nil)

(unless (require 'eglot nil t)
  (setq package-directory-list
        (cl-remove-if-not #'file-directory-p
                          (list "/usr/local/share/emacs/site-lisp/elpa"
                                (format "/usr/share/emacs/%s/site-lisp/elpa" emacs-version)
                                "/usr/share/emacs/site-lisp/elpa")))
  (package-initialize)
  (require 'eglot))

(defvar bench-file (file-truename (getenv "B_FILE")))
(defvar bench-root (file-name-as-directory (getenv "B_ROOT")))
(defvar bench-code (getenv "B_CODE"))
(defvar bench-line (string-to-number (getenv "B_LINE")))
(defvar bench-planted (getenv "B_PLANTED"))
(defvar bench-rounds (string-to-number (or (getenv "B_ROUNDS") "5")))
(defvar bench-quiet (string-to-number (or (getenv "B_QUIET") "2")))
(when (getenv "B_IDLE")
  (setq eglot-send-changes-idle-time (string-to-number (getenv "B_IDLE"))))
(when (getenv "B_EVAL") (eval (car (read-from-string (getenv "B_EVAL"))) t))

;; The README's setup, with the harness's server command.
(add-to-list 'auto-mode-alist '("\\.\\(?:urdf\\|xacro\\)\\'" . nxml-mode))
(add-to-list 'eglot-server-programs
             `((nxml-mode :language-id "xml")
               . ,(append (json-read-from-string (getenv "B_CMD")) nil)))
(add-hook 'nxml-mode-hook
          (lambda ()
            (when (and buffer-file-name
                       (string-match-p "\\.\\(?:urdf\\|xacro\\)\\'" buffer-file-name))
              (eglot-ensure))))
;; The workspace is no VCS repository here: make it the project (the LSP workspace folder).
(add-hook 'project-find-functions (lambda (_dir) (cons 'transient bench-root)))

(defvar bench-report nil)
(defvar bench-buffer nil)
(defvar bench-original nil)
(defvar bench-base 0 "Diagnostics with `bench-code' in the file as opened.")
(defvar bench-last-publish 0.0 "When the last publishDiagnostics (any file) was handled.")
(defvar bench-first-publish nil)
(defvar bench-publishes 0)
(defvar bench-published nil "The last publish for the file: (TOTAL . WITH-CODE).")
(defvar bench-poll nil)
(defvar bench-pending nil "A test of the code count that the next publish for the file may pass.")
(defvar bench-passed nil "When a publish for the file first passed `bench-pending'.")
(defvar bench-shown nil)
(defvar bench-cleared nil)
(defvar bench-edit-at nil "When the last edit was made, until its didChange is sent.")
(defvar bench-sent nil "Each edit -> its didChange sent (Eglot waits for idleness).")

(advice-add 'eglot--signal-textDocument/didChange :before
            (lambda (&rest _)
              (when (and bench-edit-at (bound-and-true-p eglot--recent-changes))
                (push (- (float-time) bench-edit-at) bench-sent)
                (setq bench-edit-at nil))))

(defun bench-put (key value) (setf (alist-get key bench-report) value))

(defun bench-write-report ()
  (let ((json-encoding-pretty-print nil))
    (with-temp-file (getenv "B_OUT") (insert (json-encode bench-report)))))

(defmacro bench-guard (&rest body)
  "BODY; on an error, a report that says so, and exit."
  `(condition-case err
       (progn ,@body)
     (error (bench-put 'ok :json-false)
            (bench-put 'error (error-message-string err))
            (bench-write-report)
            (kill-emacs 1))))

(defun bench-want (what)
  (with-temp-file (getenv "B_WANT") (insert what)))

(advice-add 'eglot-handle-notification :after
            (lambda (_server method &rest args)
              (when (eq method 'textDocument/publishDiagnostics)
                (setq bench-last-publish (float-time))
                (when (equal (bench-uri-file (plist-get args :uri)) bench-file)
                  (cl-incf bench-publishes)
                  (let ((diagnostics (append (plist-get args :diagnostics) nil)))
                    (setq bench-published
                          (cons (length diagnostics)
                                (cl-count-if (lambda (d) (equal (plist-get d :code) bench-code))
                                             diagnostics))))
                  (when (and bench-pending (not bench-passed)
                             (funcall bench-pending (cdr bench-published)))
                    (setq bench-passed (float-time)))
                  (unless bench-first-publish (setq bench-first-publish (float-time)))))))

(defun bench-uri-file (uri)
  (file-truename (url-unhex-string (string-remove-prefix "file://" uri))))

(defun bench-with-code ()
  "How many diagnostics with code `bench-code' the last publish for the file gave Eglot.
\(Not Flymake's: editing a line deletes the Flymake overlays on it, and its diagnostics with
them, before the server has seen the edit.)"
  (or (cdr bench-published) 0))

(defun bench-watch (done-p on-done &optional timeout)
  "Every 20 ms until DONE-P (called with the seconds waited): ON-DONE with them. (Edits are
timed in the publish handler, not by this.)"
  (let ((start (float-time)) (timeout (or timeout 120)))
    (when bench-poll (cancel-timer bench-poll))
    (setq bench-poll
          (run-at-time 0.02 0.02
                       (lambda ()
                         (bench-guard
                          (let ((waited (- (float-time) start)))
                            (when (> waited timeout) (error "Nothing after %s s" timeout))
                            (when (funcall done-p waited)
                              (cancel-timer bench-poll)
                              (setq bench-poll nil)
                              (funcall on-done waited)))))))))

(defun bench-quiet-then (next)
  "When no publish came for `bench-quiet' s: NEXT."
  (bench-watch (lambda (_) (> (- (float-time) bench-last-publish) bench-quiet))
               (lambda (_) (funcall next))))

(defun bench-open ()
  (interactive)
  (bench-guard (bench-open-1)))

(defun bench-open-1 ()
  (let ((start (float-time)) (shown nil))
    (find-file bench-file)
    (setq bench-buffer (current-buffer))
    (setq bench-original
          (save-excursion (goto-char (point-min)) (forward-line bench-line)
                          (buffer-substring-no-properties (point) (line-end-position))))
    (bench-watch
     (lambda (_)
       (when (and (not shown) (buffer-live-p bench-buffer)
                  (with-current-buffer bench-buffer (flymake-diagnostics)))
         (setq shown (float-time)))
       (and bench-first-publish
            (> (- (float-time) bench-last-publish) bench-quiet)))
     (lambda (_)
       (bench-put 'open_first_publish (and bench-first-publish (- bench-first-publish start)))
       (bench-put 'open_first_shown (and shown (- shown start)))
       (bench-put 'open_quiet (- bench-last-publish start))
       (bench-put 'open_diagnostics (car bench-published))
       (bench-put 'open_displayed (with-current-buffer bench-buffer
                                    (length (flymake-diagnostics))))
       (setq bench-base (bench-with-code))
       (bench-put 'open_with_code bench-base)
       (bench-put 'open_publishes bench-publishes)
       (bench-want "plant 1")))))

(defun bench-set-line (text)
  (setq bench-edit-at (float-time))
  (with-current-buffer bench-buffer
    (save-excursion
      (goto-char (point-min))
      (forward-line bench-line)
      (delete-region (point) (line-end-position))
      (insert text))))

(defun bench-timed-edit (text test on-done)
  "Set the line to TEXT; when a publish for the file passes TEST: ON-DONE with the seconds
from the edit to that publish handled."
  (let ((start (float-time)))
    (setq bench-pending test bench-passed nil)
    (bench-set-line text)
    (bench-watch (lambda (_) bench-passed)
                 (lambda (_)
                   (setq bench-pending nil)
                   (funcall on-done (- bench-passed start))))))

(defun bench-plant ()
  (interactive)
  (bench-timed-edit bench-planted (lambda (n) (> n bench-base))
                    (lambda (waited)
                      (push waited bench-shown)
                      (bench-quiet-then
                       (lambda () (bench-want (format "revert %d" (length bench-shown))))))))

(defun bench-revert ()
  (interactive)
  (bench-timed-edit bench-original (lambda (n) (<= n bench-base))
                    (lambda (waited)
                      (push waited bench-cleared)
                      (bench-quiet-then
                       (lambda ()
                         (if (< (length bench-cleared) bench-rounds)
                             (bench-want (format "plant %d" (1+ (length bench-cleared))))
                           (bench-finish)))))))

(defun bench-finish ()
  (bench-put 'editor (format "Emacs %s, Eglot %s" emacs-version
                             (let ((d (cadr (assq 'eglot package-alist))))
                               (if d (package-version-join (package-desc-version d)) "built in"))))
  (bench-put 'idle eglot-send-changes-idle-time)
  (bench-put 'shown (vconcat (reverse bench-shown)))
  (bench-put 'cleared (vconcat (reverse bench-cleared)))
  (bench-put 'sent (vconcat (reverse bench-sent)))
  (bench-put 'cpu (float-time (get-internal-run-time)))
  (bench-put 'events_chars (cl-loop for b in (buffer-list)       ; Eglot's log of messages
                                    when (string-match-p "events\\*\\'" (buffer-name b))
                                    sum (buffer-size b)))
  (bench-put 'ok t)
  (with-current-buffer bench-buffer (set-buffer-modified-p nil))
  (bench-write-report)
  (with-current-buffer bench-buffer (ignore-errors (eglot-shutdown (eglot-current-server))))
  (bench-want "done")
  (kill-emacs 0))

(global-set-key (kbd "C-c o") #'bench-open)
(global-set-key (kbd "C-c p") #'bench-plant)
(global-set-key (kbd "C-c r") #'bench-revert)
(add-hook 'emacs-startup-hook (lambda () (run-at-time 0.3 nil #'bench-want "open")))

;;; editor_latency.el ends here
